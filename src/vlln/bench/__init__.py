"""`vlln bench ...`: speed and memory figures, printed as JSON lines or a table."""
