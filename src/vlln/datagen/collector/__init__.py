"""Trajectory collection: a privileged frontier explorer that asks the oracle as it goes."""
