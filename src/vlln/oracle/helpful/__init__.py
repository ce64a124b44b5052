"""The helpful oracle: the paper's answers, and exact grounded help beyond its questions."""
