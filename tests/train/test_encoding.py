"""Conversations become model inputs: images expanded in place, loss only on the assistant."""

from __future__ import annotations

from pathlib import Path

import pytest
import torch
from PIL import Image

from vlln.agents.local.encoding import IGNORE_INDEX, ChatEncoder, to_messages
from vlln.errors import ConfigError
from vlln.prompt import Turn
from vlln.train.data import SftCollator, load_rgb, read_export

TURNS = (
    Turn("human", "Find the chair. <image> In front of you is <image>."),
    Turn("gpt", "<talk>Which room is it in?"),
    Turn("human", "It is in the kitchen."),
    Turn("gpt", "<move>←←"),
)


def _images(count: int) -> list[Image.Image]:
    return [Image.new("RGB", (384, 384), (40 * i, 90, 200)) for i in range(count)]


def test_image_tags_become_image_parts_in_place() -> None:
    messages = to_messages(TURNS[:2])
    assert messages[0] == {
        "role": "user",
        "content": [
            {"type": "text", "text": "Find the chair. "},
            {"type": "image"},
            {"type": "text", "text": " In front of you is "},
            {"type": "image"},
            {"type": "text", "text": "."},
        ],
    }
    assert messages[1] == {"role": "assistant", "content": "<talk>Which room is it in?"}
    with pytest.raises(ConfigError, match="'human' or 'gpt'"):
        to_messages([Turn("system", "hi")])  # type: ignore[arg-type]


@pytest.mark.slow
def test_labels_keep_exactly_the_assistant_turns(tiny_model: Path) -> None:
    encoder = ChatEncoder.load(tiny_model)
    short = (Turn("human", "Go. <image>"), Turn("gpt", "<move>STOP"))
    texts = [encoder.render(TURNS, False), encoder.render(short, False)]
    batch = encoder.encode(texts, [_images(2), _images(1)])
    labels = encoder.assistant_labels(batch["input_ids"], batch["attention_mask"])
    tokenizer = encoder.tokenizer
    kept = [tokenizer.decode(row[row != IGNORE_INDEX]) for row in labels]
    assert kept == [
        "<talk>Which room is it in?<|im_end|><move>←←<|im_end|>",
        "<move>STOP<|im_end|>",
    ]
    # Padding (the short row is padded on the right) and image tokens never count.
    assert (labels[batch["attention_mask"] == 0] == IGNORE_INDEX).all()
    assert (labels[batch["input_ids"] == encoder.image_token_id] == IGNORE_INDEX).all()
    assert batch["attention_mask"][1, -1] == 0


@pytest.mark.slow
def test_each_image_placeholder_is_repeated_once_per_merged_patch(tiny_model: Path) -> None:
    encoder = ChatEncoder.load(tiny_model)
    text = encoder.render(TURNS, add_generation_prompt=False)
    batch = encoder.encode([text], [_images(2)])
    grid = batch["image_grid_thw"]
    expected = int(grid.prod(dim=1).sum()) // encoder.merge_area
    assert int((batch["input_ids"] == encoder.image_token_id).sum()) == expected
    assert torch.equal(
        batch["mm_token_type_ids"], (batch["input_ids"] == encoder.image_token_id).int()
    )
    prompt = encoder.render(TURNS[:1], add_generation_prompt=True)
    assert prompt.endswith("<|im_start|>assistant\n")


@pytest.mark.slow
def test_a_conversation_needs_one_image_per_tag(tiny_model: Path) -> None:
    encoder = ChatEncoder.load(tiny_model)
    text = encoder.render(TURNS, add_generation_prompt=False)
    with pytest.raises(ConfigError, match="2 image placeholders but 1 images"):
        encoder.encode([text], [_images(1)])


@pytest.mark.slow
def test_export_samples_train_on_exactly_their_assistant_turns(
    sft_export: Path, tiny_model: Path
) -> None:
    samples = read_export(sft_export)
    collate = SftCollator(ChatEncoder.load(tiny_model))
    chosen = [samples[0], *[s for s in samples if len(s.turns) > 2][:2], samples[-1]]
    batch = collate(chosen)
    assert len(batch["image_grid_thw"]) == sum(len(sample.images) for sample in chosen)
    tokenizer = collate.encoder.tokenizer
    for row, sample in zip(batch["labels"], chosen, strict=True):
        learnt = "".join(turn.text + "<|im_end|>" for turn in sample.turns if turn.role == "gpt")
        assert tokenizer.decode(row[row != IGNORE_INDEX]) == learnt


@pytest.mark.slow
@pytest.mark.parametrize("cache_bytes", [0, 512 * 2**20])
def test_the_collator_keeps_frames_without_changing_a_batch(
    sft_export: Path, tiny_model: Path, cache_bytes: int
) -> None:
    samples = read_export(sft_export)
    encoder = ChatEncoder.load(tiny_model)
    chosen = [s for s in samples if len(s.images) > 1][:3]
    texts = [encoder.render(s.turns, add_generation_prompt=False) for s in chosen]
    direct = encoder.encode(texts, [[load_rgb(p) for p in s.images] for s in chosen])
    collate = SftCollator(encoder, cache_bytes=cache_bytes)
    first = collate(chosen)
    collate(chosen[::-1])  # the same frames again, in another order
    for batch in (first, collate(chosen)):
        assert set(batch) == {*direct, "labels"}
        for key, tensor in direct.items():
            assert torch.equal(batch[key], tensor), key
    held = len(collate._cache)
    assert held == (0 if cache_bytes == 0 else len({p for s in chosen for p in s.images}))
