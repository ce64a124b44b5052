"""vlln: an open, pip-installable implementation of VL-LN Bench.

Interactive instance-goal navigation with dialog, on procedural houses rendered on the CPU.
"""

__version__ = "0.1.0"
__all__ = ["__version__"]
