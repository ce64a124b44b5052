"""The ``vlln`` agent's local transformers model: loading, encoding conversations (shared
with training) and greedy generation. Needs the ``model`` extra."""
