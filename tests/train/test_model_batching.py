"""The tiny Qwen2.5-VL behind :class:`BatchingModel`: calls that arrive together are answered
in one left-padded batch, each with the reply it gets alone."""

from __future__ import annotations

import asyncio
import io
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from vlln.agents.local.backend import TransformersBackend
from vlln.agents.local.batching import BatchingModel
from vlln.agents.model.backend import ModelReply
from vlln.prompt import Conversation, DialogExchange, build_conversation, connective_for


def _jpeg(seed: int) -> bytes:
    pixels = (np.random.default_rng(seed).random((64, 64, 3)) * 255).astype(np.uint8)
    data = io.BytesIO()
    Image.fromarray(pixels).save(data, format="JPEG")
    return data.getvalue()


def _calls() -> list[tuple[Conversation, list[bytes]]]:
    """Prompts of different lengths and image counts, so a batch of them is padded."""
    calls = []
    for index in range(4):
        dialogs = [DialogExchange(0, "Which room is it in?", "The kitchen.")] * (index % 2)
        conversation = build_conversation(
            "Search for the chair" + " near the bed" * index,
            index,
            dialogs,
            connective=connective_for(index, "episode", index),
        )
        calls.append((conversation, [_jpeg(10 * index + k) for k in range(index + 1)]))
    return calls


def _answer(reply: ModelReply) -> tuple[object, ...]:
    return reply.text, reply.error, reply.prompt_tokens, reply.completion_tokens


@pytest.mark.slow
def test_calls_arriving_together_are_batched_and_answered_as_alone(tiny_model: Path) -> None:
    backend = TransformersBackend(tiny_model, "cpu", max_new_tokens=24)
    calls = _calls()
    alone = [backend.generate(conversation, images) for conversation, images in calls]
    assert len({reply.prompt_tokens for reply in alone}) == len(calls)
    model = BatchingModel(backend, max_batch=8)

    async def together() -> list[ModelReply]:
        return await asyncio.gather(*(model.generate(c, images) for c, images in calls))

    batched = asyncio.run(together())
    assert [_answer(reply) for reply in batched] == [_answer(reply) for reply in alone]
    # All four arrived before the model started: one forward pass answered them.
    assert (model.requests, model.batches, model.largest_batch) == (4, 1, 4)
    assert len({reply.latency_ms for reply in batched}) == 1


@pytest.mark.slow
def test_batches_hold_at_most_max_batch_calls(tiny_model: Path) -> None:
    backend = TransformersBackend(tiny_model, "cpu", max_new_tokens=4)
    model = BatchingModel(backend, max_batch=2)
    calls = _calls()

    async def together() -> list[ModelReply]:
        return await asyncio.gather(*(model.generate(c, images) for c, images in calls))

    asyncio.run(together())
    assert (model.requests, model.batches, model.largest_batch) == (4, 2, 2)
