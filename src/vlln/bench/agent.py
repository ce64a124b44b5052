"""`vlln bench agent`: what a model agent's step costs outside the model.

Two figures matter on top of the model's own latency. ``prompt_and_read_ms`` is the work every
decision does: build the shared prompt at a late frame (8 evenly spaced history frames plus
the frames of earlier dialogs; :func:`vlln.prompt.build_conversation`) and read a reply
(:func:`vlln.prompt.read_output`, over a mix of valid and malformed replies); the target is
2 ms. Image preparation is reported apart, because it depends on the pictures and not on the
prompt: a level frame encoded as the model sees it (JPEG, 384x384, once per frame), the
look-down frame (JPEG 640x480, once per look-down), and the chat request of the ``openai-vlm``
backend (base64 data URLs of every picture, once per call). The pictures are real renders of
a generated house.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from vlln.agents.model.openai_vlm import chat_messages
from vlln.bench.figures import Figure, emit, median_seconds
from vlln.bench.settings import AgentBench
from vlln.prompt import (
    Conversation,
    DialogExchange,
    build_conversation,
    connective_for,
    read_output,
)
from vlln.prompt.images import model_image
from vlln.sim.agent import AgentState
from vlln.sim.simulator import Simulator
from vlln.world.generator import generate_house

FRAME = 120  # a decision late in an episode: the history is full
DIALOG_FRAMES = (17, 55, 98)  # earlier questions, shown in the history with their answers
REPLIES = (
    "<move>←←",
    "<move>STOP",
    "<talk>Is the chair next to the window?",
    "<move>↓",
    "<move>→",
    "I think I should turn left now.",
    "<move>fly up",
    "<talk>" + "where is it " * 20,
)
LOOK_DOWN_REPLIES = ("<move>312 401", "<move>12", "<move>640 480")


def run_agent_benchmark(settings: AgentBench) -> list[Figure]:
    """Measure and print the model agent's per-step costs outside the model."""
    seed, repeats, as_json = settings.seed, settings.repeats, settings.as_json
    figures: list[Figure] = []

    def record(metric: str, value: float, unit: str) -> None:
        figure = Figure(metric, value, unit)
        figures.append(figure)
        emit(figure, as_json)

    dialogs = [
        DialogExchange(frame, "Which room is it in?", "It is in the living room.")
        for frame in DIALOG_FRAMES
    ]

    def build(heard: list[DialogExchange]) -> Conversation:
        connective = connective_for(seed, "bench", FRAME)
        return build_conversation("Search for the chair.", FRAME, heard, connective=connective)

    def read() -> None:
        for text in REPLIES:
            read_output(text, look_down=False)
        for text in LOOK_DOWN_REPLIES:
            read_output(text, look_down=True)

    def per_call_ms(run: Callable[[], object], calls: int) -> float:
        return median_seconds(lambda: [run() for _ in range(repeats)], 5) / repeats / calls * 1e3

    build_ms = per_call_ms(lambda: build([]), 1)
    read_ms = per_call_ms(read, len(REPLIES) + len(LOOK_DOWN_REPLIES))
    record("history_images", float(len(build([]).images) - 1), "images")
    record("prompt_build_ms", build_ms, "ms")
    record("output_read_ms", read_ms, "ms")
    record("prompt_and_read_ms", build_ms + read_ms, "ms")
    conversation = build(dialogs)  # 8 spaced frames plus 3 dialog frames and their exchanges
    record("prompt_build_dialogs_ms", per_call_ms(lambda: build(dialogs), 1), "ms")

    level, down = _rendered_frames(seed)
    record("level_image_ms", median_seconds(lambda: model_image(level, "level"), 21) * 1e3, "ms")
    record("down_image_ms", median_seconds(lambda: model_image(down, "down"), 21) * 1e3, "ms")
    pictures = [model_image(level, "level")] * len(conversation.images)
    record("level_image_kb", len(pictures[0]) / 1024.0, "kB")

    def request_body() -> str:
        messages = chat_messages(conversation, pictures)
        return json.dumps({"messages": [m.to_json() for m in messages]})

    record("request_build_ms", median_seconds(request_body, 21) * 1e3, "ms")
    record("request_kb", len(request_body()) / 1024.0, "kB")
    return figures


def _rendered_frames(seed: int) -> tuple[NDArray[np.uint8], NDArray[np.uint8]]:
    """A level and a look-down view from the middle of a generated house."""
    with Simulator(generate_house(seed)) as sim:
        rng = np.random.default_rng(seed)
        x, z = sim.grid.sample_navigable_point(rng, sim.grid.largest_component())
        yaw = float(rng.uniform(-math.pi, math.pi))
        level = sim.render(AgentState((x, sim.grid.floor_y, z), yaw, 0.0)).rgb.copy()
        down = sim.render(AgentState((x, sim.grid.floor_y, z), yaw, -math.radians(30))).rgb
        return level, down.copy()
