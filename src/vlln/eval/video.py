"""Episode videos: the first-person view beside the top-down map, questions captioned.

Frames are re-rendered from an episode record alone, as :mod:`vlln.eval.episode_map` draws
maps: every movement action (FORWARD, TURN) moves the camera to the next recorded pose
(``positions``: x, z, yaw), LOOK actions tilt it by the motion's step, and STOP, TALK and
failed actions keep the view. One action is one frame; a question holds its frame
``hold_s`` seconds and its caption (question and answer, grey when refused) stays for
``caption_s``. The map is drawn once with matplotlib; the trail and the agent are drawn on it
per frame. In a house with several storeys the map shows the storey the agent is on (from the
record's ``heights``) and the trail's part on it. Encoding is H.264 in MP4 (yuv420p,
``faststart`` for the web) with PyAV, the video extra.
"""

from __future__ import annotations

import math
import textwrap
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from numpy.typing import NDArray
from PIL import Image, ImageDraw, ImageFont
from pydantic import Field

from vlln.config import Count, settings_dataclass
from vlln.errors import ConfigError
from vlln.extras import install_command
from vlln.files import writing
from vlln.sim.agent import Action, AgentState
from vlln.sim.simulator import Simulator
from vlln.tasks.record import DialogTurn, EpisodeRecord
from vlln.viz.topdown import draw_house, storey_name, storeys_of
from vlln.world.frame import heading_vector
from vlln.world.model import House

_MOVES = {Action.MOVE_FORWARD.name, Action.TURN_LEFT.name, Action.TURN_RIGHT.name}
Rgb = NDArray[np.uint8]


Even = Annotated[int, Field(multiple_of=2)]


@settings_dataclass
class VideoConfig:
    """Frame rate, caption timing and panel sizes (pixels; even, as yuv420p needs)."""

    fps: Count = 4
    hold_s: float = 1.5
    caption_s: float = 4.0
    map_size: Even = 480
    caption_height: Even = 112


@dataclass(frozen=True)
class _Step:
    state: AgentState
    pose_index: int
    action: str
    turn: DialogTurn | None  # the question asked by this action


def write_episode_video(
    record: EpisodeRecord, house: House, sim: Simulator, path: Path, config: VideoConfig
) -> float:
    """Write the MP4 of ``record`` (played in ``house``, rendered by ``sim``) to ``path``;
    returns its duration in seconds."""
    try:
        import av
    except ImportError:
        raise ConfigError(f"episode videos need PyAV: {install_command('video')}") from None
    bases, to_pixel = map_images(house, record, config.map_size)
    camera = sim.config.camera
    width = camera.width + config.map_size
    height = max(camera.height, config.map_size) + config.caption_height
    if width % 2 or height % 2:
        raise ConfigError(f"video size {width}x{height} must be even; use an even camera size")
    with writing(path):  # a video cut short stays partial: a rerun writes it again
        path.parent.mkdir(parents=True, exist_ok=True)
        partial = path.with_name(f".{path.name}.partial.mp4")  # renamed once complete
        frames = 0
        with av.open(str(partial), "w", options={"movflags": "faststart"}) as container:
            stream: Any = container.add_stream("libx264", rate=config.fps)
            stream.width, stream.height, stream.pix_fmt = width, height, "yuv420p"
            stream.options = {"crf": "26", "preset": "veryfast"}
            for image in _frames(record, sim, bases, to_pixel, (width, height), config):
                frame = av.VideoFrame.from_ndarray(image, format="rgb24")
                for packet in stream.encode(frame):
                    container.mux(packet)
                frames += 1
            for packet in stream.encode():
                container.mux(packet)
        partial.replace(path)
    return frames / config.fps


def replay(record: EpisodeRecord, sim: Simulator) -> Iterator[_Step]:
    """The camera pose after every action of ``record`` (module doc)."""
    if not record.positions:
        raise ConfigError(f"episode {record.episode_id} has no recorded positions to replay")
    motion = sim.config.motion
    step, low, high = (
        math.radians(v) for v in (motion.tilt_step_deg, motion.min_tilt_deg, motion.max_tilt_deg)
    )
    pose, tilt, questions = 0, 0.0, iter(record.dialog)
    several = sim.storeys is not None
    if several and len(record.heights) != len(record.positions):
        raise ConfigError(
            f"episode {record.episode_id} is in a house with several storeys but its record has "
            "no heights; play it again with this version of vlln to record them"
        )

    def state() -> AgentState:
        x, z, yaw = record.positions[pose]
        y = record.heights[pose] if several else sim.grid.floor_y
        return AgentState((x, y, z), yaw, tilt)

    yield _Step(state(), pose, "START", None)
    for action in record.actions:
        turn = None
        if action in _MOVES:
            pose = min(pose + 1, len(record.positions) - 1)
        elif action == Action.LOOK_UP.name:
            tilt = min(tilt + step, high)
        elif action == Action.LOOK_DOWN.name:
            tilt = max(tilt - step, low)
        elif action == "TALK":
            turn = next(questions, None)
        yield _Step(state(), pose, action, turn)


def _frames(
    record: EpisodeRecord,
    sim: Simulator,
    bases: dict[int, Rgb],
    to_pixel: Any,
    size: tuple[int, int],
    config: VideoConfig,
) -> Iterator[Rgb]:
    font = ImageFont.load_default(size=18)
    small = ImageFont.load_default(size=15)
    trail: list[tuple[tuple[float, float], int]] = []  # map pixel and storey
    caption: tuple[DialogTurn, int] | None = None
    for index, step in enumerate(replay(record, sim)):
        x, z, yaw = record.positions[step.pose_index]
        storey = 0 if sim.storeys is None else sim.storeys.level_of(step.state.position[1])
        if not trail or trail[-1] != (to_pixel(x, z), storey):
            trail.append((to_pixel(x, z), storey))
        view = sim.render(step.state).rgb
        canvas = Image.new("RGB", size, "white")
        canvas.paste(Image.fromarray(view), (0, 0))
        panel = Image.fromarray(bases[storey])
        _draw_agent(ImageDraw.Draw(panel), _trail_on(trail, storey), yaw, to_pixel(x, z))
        canvas.paste(panel, (view.shape[1], 0))
        draw = ImageDraw.Draw(canvas)
        status = f"{record.episode_id}  action {index}: {step.action}"
        draw.text((8, 6), status, fill="white", font=small, stroke_width=2, stroke_fill="black")
        repeats = 1
        if step.turn is not None:
            caption = (step.turn, 0)
            repeats = max(1, round(config.hold_s * config.fps))
        for _ in range(repeats):
            if caption is not None:
                turn, shown = caption
                _draw_caption(draw, turn, size, config.caption_height, font)
                caption = (turn, shown + 1) if shown + 1 < config.caption_s * config.fps else None
            yield np.asarray(canvas, dtype=np.uint8)


def _trail_on(
    trail: list[tuple[tuple[float, float], int]], storey: int
) -> list[list[tuple[float, float]]]:
    """The pieces of the trail on one storey (a climb leaves the storey at the stairs)."""
    pieces: list[list[tuple[float, float]]] = []
    previous = None
    for point, level in trail:
        if level == storey:
            if previous != storey:
                pieces.append([])
            pieces[-1].append(point)
        previous = level
    return pieces


def _draw_agent(
    draw: ImageDraw.ImageDraw,
    trail: list[list[tuple[float, float]]],
    yaw: float,
    at: tuple[float, float],
) -> None:
    for piece in trail:
        if len(piece) > 1:
            draw.line(piece, fill=(30, 90, 220), width=3)
    dx, dz = heading_vector(yaw)
    tip = (at[0] + 16 * dx, at[1] + 16 * dz)  # map rows grow with z (-z is up)
    draw.line([at, tip], fill=(200, 0, 0), width=3)
    draw.ellipse([at[0] - 6, at[1] - 6, at[0] + 6, at[1] + 6], fill=(200, 0, 0))


def _draw_caption(
    draw: ImageDraw.ImageDraw,
    turn: DialogTurn,
    size: tuple[int, int],
    height: int,
    font: ImageFont.FreeTypeFont | ImageFont.ImageFont,
) -> None:
    top = size[1] - height
    draw.rectangle([0, top, size[0], size[1]], fill=(245, 245, 245))
    answer_colour = (20, 110, 40) if turn.answered else (130, 130, 130)
    width = max(20, size[0] // 10)
    lines = [("Q: " + line, (20, 20, 20)) for line in textwrap.wrap(turn.question, width)[:2]]
    lines += [("A: " + line, answer_colour) for line in textwrap.wrap(turn.answer, width)[:2]]
    for row, (text, colour) in enumerate(lines):
        draw.text((10, top + 6 + 25 * row), text, fill=colour, font=font)


def map_images(house: House, record: EpisodeRecord, size: int) -> tuple[dict[int, Rgb], Any]:
    """The floor plan of every storey as a ``size``² image, and the function from (x, z) to
    their pixels (one frame for all storeys)."""
    xs = [p[0] for room in house.rooms for p in room.polygon]
    zs = [p[1] for room in house.rooms for p in room.polygon]
    cx, cz = (min(xs) + max(xs)) / 2, (min(zs) + max(zs)) / 2
    half = max(max(xs) - min(xs), max(zs) - min(zs)) / 2 + 0.5
    storeys = storeys_of(house)
    images = {}
    for storey in storeys:
        figure = plt.figure(figsize=(size / 100, size / 100), dpi=100)
        try:
            axes = figure.add_axes((0, 0, 1, 1))
            several = len(storeys) > 1
            draw_house(
                axes, house, label_objects=False, highlight=record.target_ids,
                storey=storey if several else None,
            )  # fmt: skip
            if several:
                axes.text(0.02, 0.02, storey_name(storey), transform=axes.transAxes, fontsize=11)
            axes.set_xlim(cx - half, cx + half)
            axes.set_ylim(cz + half, cz - half)  # z grows downwards, as in to_pixel
            axes.set_aspect("equal")
            axes.axis("off")
            figure.canvas.draw()
            canvas: Any = figure.canvas
            images[storey] = np.asarray(canvas.buffer_rgba())[..., :3].copy()
        finally:
            plt.close(figure)

    def to_pixel(x: float, z: float) -> tuple[float, float]:
        return ((x - cx + half) / (2 * half) * size, (z - cz + half) / (2 * half) * size)

    return images, to_pixel
