"""Tasks (IIGN, IGN, ObjectNav): episodes, the environment, and metrics over finished records."""
