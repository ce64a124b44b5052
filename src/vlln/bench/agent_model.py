"""`vlln bench agent`, the model part: decisions per second of the ``vlln`` agent's local
model, measured with the tiny randomly initialised Qwen2.5-VL of :mod:`vlln.train.scratch` on a
late-episode prompt (8 history frames, 3 dialog frames, the current frame; real renders).

The figures time the backend's whole call (chat template, image processing, greedy decoding
up to 128 tokens); a random model rarely ends its turn early, so ``tokens_per_s`` is the
steadier figure. They describe the machine's overhead, not a real model's speed: the
Qwen2.5-VL-3B figures need a GPU and are only measured when one is present.
"""

from __future__ import annotations

import io
import json
import tempfile
import time

from PIL import Image

from vlln.agents.local.backend import MAX_NEW_TOKENS
from vlln.agents.local.dependencies import require_model_extra
from vlln.bench.figures import Figure, emit
from vlln.bench.settings import AgentBench
from vlln.errors import ConfigError

BATCH = 4  # conversations answered in one padded forward pass
PASSES = 3  # timed decisions per thread count: a model step is slow, unlike the agent's


def run_model_benchmark(
    settings: AgentBench, passes: int = PASSES, max_new_tokens: int = MAX_NEW_TOKENS
) -> list[Figure]:
    """Measure and print the tiny model's decisions per second (CPU unless a GPU is present);
    ``passes`` and ``max_new_tokens`` below their defaults only to keep a smoke run short."""
    seed, as_json = settings.seed, settings.as_json
    try:
        require_model_extra()
    except ConfigError as error:
        _note(f"model figures skipped: {error}", as_json)
        return []
    import torch

    from vlln.agents.local.backend import ChatRequest, TransformersBackend
    from vlln.bench.agent import DIALOG_FRAMES, FRAME, _rendered_frames
    from vlln.prompt import DialogExchange, build_conversation, connective_for
    from vlln.prompt.images import model_image
    from vlln.train.scratch import build_tiny_model

    figures: list[Figure] = []

    def record(metric: str, value: float, unit: str) -> None:
        figure = Figure(metric, value, unit)
        figures.append(figure)
        emit(figure, as_json)

    dialogs = [DialogExchange(f, "Which room is it in?", "The kitchen.") for f in DIALOG_FRAMES]
    connective = connective_for(seed, "bench", FRAME)
    conversation = build_conversation(
        "Search for the chair.", FRAME, dialogs, connective=connective
    )
    level, _ = _rendered_frames(seed)
    picture = model_image(level, "level")
    with tempfile.TemporaryDirectory(prefix="vlln-bench-model-") as folder:
        backend = TransformersBackend(
            build_tiny_model(folder, seed=seed), max_new_tokens=max_new_tokens
        )
    images = [picture] * len(conversation.images)
    with Image.open(io.BytesIO(picture)) as opened:
        batch = [ChatRequest(conversation, tuple(opened.convert("RGB") for _ in images))] * BATCH
    device = backend.device
    default_threads = torch.get_num_threads()
    # Both torch's default thread count and one thread: on a busy shared machine the default
    # can be many times slower than one thread.
    for threads in sorted({default_threads, 1}, reverse=True):
        torch.set_num_threads(threads)
        backend.generate(conversation, images)  # warm-up
        tokens, started = 0, time.perf_counter()
        for _ in range(passes):
            reply = backend.generate(conversation, images)
            tokens += reply.completion_tokens
        seconds = time.perf_counter() - started
        where = f"{device}_threads{threads}"
        record(f"tiny_model_steps_per_s_{where}", passes / seconds, "steps/s")
        record(f"tiny_model_tokens_per_s_{where}", tokens / seconds, "tokens/s")
        started = time.perf_counter()
        backend.generate_batch(batch)
        batch_rate = BATCH / (time.perf_counter() - started)
        record(f"tiny_model_batch{BATCH}_steps_per_s_{where}", batch_rate, "steps/s")
    torch.set_num_threads(default_threads)
    record("tiny_model_prompt_tokens", float(reply.prompt_tokens), "tokens")
    _note(
        "no Qwen2.5-VL-3B figures: they need a GPU machine and have not been measured; "
        "the tiny model's figures show the overhead around a model, not a real model's speed",
        as_json,
    )
    return figures


def _note(text: str, as_json: bool) -> None:
    print(json.dumps({"note": text}) if as_json else f"note: {text}")
