"""The house model, its import/export, the object catalogue and the procedural generator."""
