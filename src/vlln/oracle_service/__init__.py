"""The oracle as an HTTP service, for agents in any language and for real robots."""
