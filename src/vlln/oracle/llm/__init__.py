"""Language-model backends for the oracle: one small client protocol, an offline model and an
OpenAI-compatible chat-completions client with caching and cost accounting."""
