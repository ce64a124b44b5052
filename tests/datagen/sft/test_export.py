"""export_sft on a hand-made dataset of real renders: the exact format, the pixel goals, the
files it writes, and its settings."""

from __future__ import annotations

import itertools
import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from PIL import Image
from tests.datagen.sft.conftest import HandDataset
from tests.datagen.sft.samples import (
    PIXEL_OUTPUT,
    episode_samples,
    read_samples,
    sample_frame,
)

from vlln.datagen.layout import HouseDataset
from vlln.datagen.sft import SftConfig, export_sft
from vlln.sim.agent import AgentState
from vlln.sim.camera import CameraSpec
from vlln.tasks.spec import REFUSAL_MESSAGE
from vlln.world.frame import quaternion_to_yaw

DOWN_TILT = math.radians(-30.0)
INTRO = (
    "You are an autonomous navigation assistant. Your task is to search for the bathtub. You "
    "may either move or talk to an oracle. If you choose to move, first output TILT DOWN (↓), "
    "and then predict the next waypoint coordinates on the floor-view image. If the target is "
    "reached, output STOP."
)


def human(value: str) -> dict[str, str]:
    return {"from": "human", "value": value}


def gpt(value: str) -> dict[str, str]:
    return {"from": "gpt", "value": value}


def projected_pixel(at: AgentState, later: AgentState) -> tuple[int, int]:
    """Where the feet at ``later`` show on the look-down image taken at ``at``: the camera's
    view matrix and pinhole intrinsics, nearest pixel centre with halves rounded up."""
    spec = CameraSpec()
    view = spec.view_matrix(at.position, at.yaw, DOWN_TILT)
    x, y, z = view[:3, :3] @ np.asarray(later.position) + view[:3, 3]
    fx, fy, cx, cy = spec.intrinsics()
    u, v = cx + fx * x / -z, cy - fy * y / -z
    return math.floor(u + 0.5 + 1e-6), math.floor(v + 0.5 + 1e-6)


def test_golden_trajectory_is_exported_in_the_prompt_format(
    hand_dataset: HandDataset, default_export: Path
) -> None:
    house, states = hand_dataset.house, hand_dataset.states[0]
    walked = np.subtract(states[6].position, states[2].position)
    assert np.hypot(walked[0], walked[2]) == pytest.approx(1.0)  # four 0.25 m steps
    u, v = projected_pixel(states[2], states[6])
    assert u == 320  # straight ahead: the tie between columns 319 and 320 goes up

    def level(frame: int) -> str:
        return f"images/{house}/episode_000000/level_{frame:06d}.jpg"

    def down(frame: int) -> str:
        return f"images/{house}/episode_000000/down_{frame:06d}.jpg"

    first = "<|navigator|> What colour is the bathtub? <|oracle|> It is white."
    second = "<|navigator|> Is the bathtub in the room on my right? <|oracle|> Yes, it is."
    expected = [
        {
            "id": f"{house}/episode_000000/frame_000000",
            "images": [level(0)],
            "conversations": [
                human(
                    f"{INTRO} You have no historical observations yet. You have no previous "
                    "look-down image. In front of you is <image>."
                ),
                gpt("<talk>What colour is the bathtub?"),
                human("It is white."),
                gpt("<move>←←"),
            ],
        },
        {
            "id": f"{house}/episode_000000/frame_000002",
            "images": [level(0), level(1), level(2), down(2)],
            "conversations": [
                human(
                    f"{INTRO} These are your historical observations: <image> <image> "
                    f"<dialog> {first}</dialog>. You have no previous look-down image. "
                    "In front of you is <image>."
                ),
                gpt("<move>↓"),
                human("You can see <image>. Locate the goal location on the floor in this image."),
                gpt(f"<move>{u} {v}"),
            ],
        },
        {
            "id": f"{house}/episode_000000/frame_000006",
            "images": [*(level(f) for f in range(6)), down(2), level(6)],
            "conversations": [
                human(
                    f"{INTRO} These are your historical observations: <image> <image> <image> "
                    f"<image> <image> <image> <dialog> {first}</dialog>. Your previous "
                    "look-down image is <image>. In front of you is <image>."
                ),
                gpt("<talk>Is the bathtub in the room on my right?"),
                human("Yes, it is."),
                gpt("<move>→"),
            ],
        },
        {
            "id": f"{house}/episode_000000/frame_000007",
            "images": [*(level(f) for f in range(7)), down(2), level(7)],
            "conversations": [
                human(
                    f"{INTRO} These are your historical observations: <image> <image> <image> "
                    f"<image> <image> <image> <image> <dialog> {first} {second}</dialog>. Your "
                    "previous look-down image is <image>. In front of you is <image>."
                ),
                gpt("<move>STOP"),
            ],
        },
    ]
    assert episode_samples(read_samples(default_export), 0) == expected


def test_every_pixel_goal_back_projects_onto_where_the_agent_went(
    hand_dataset: HandDataset, default_export: Path
) -> None:
    dataset = HouseDataset(hand_dataset.root / "trajectories" / hand_dataset.house)
    spec = CameraSpec()
    samples = read_samples(default_export)
    checked = 0
    for sample, after in itertools.pairwise(samples):
        match = PIXEL_OUTPUT.fullmatch(sample["conversations"][-1]["value"])
        if match is None:
            continue
        (episode, frame), (next_episode, goal_frame) = sample_frame(sample), sample_frame(after)
        assert next_episode == episode  # a trajectory never ends on a pixel goal
        assert sample["images"][-1].endswith(f"/down_{frame:06d}.jpg")
        u, v = int(match[1]), int(match[2])
        frames = dataset.frames(episode)
        depth = dataset.depth("down", episode, frame)[v, u]
        feet = frames["agent_position"][frame]
        yaw = quaternion_to_yaw(list(frames["agent_rotation"][frame]))
        point = spec.unproject(u, v, depth, feet, yaw, DOWN_TILT)
        target = frames["agent_position"][goal_frame]
        assert np.linalg.norm(point - target) < 0.3, sample["id"]
        assert np.linalg.norm(target - feet) > 0.5  # nearer floor is out of the image
        checked += 1
    assert checked >= 5


def test_output_loads_with_hugging_face_datasets(default_export: Path, tmp_path: Path) -> None:
    import datasets

    datasets.disable_progress_bars()
    table = datasets.load_dataset(
        "json",
        data_files=str(default_export / "sft.jsonl"),
        cache_dir=str(tmp_path / "hf_cache"),
        split="train",
    )
    assert table.num_rows == len(read_samples(default_export)) > 0
    for row in table:
        turns = row["conversations"]
        speakers = [turn["from"] for turn in turns]
        assert speakers == ["human", "gpt"] * (len(turns) // 2)
        assert sum(turn["value"].count("<image>") for turn in turns) == len(row["images"])
        for path in row["images"]:
            with Image.open(default_export / path) as image:
                assert image.format == "JPEG"
                size = (640, 480) if "/down_" in path else (384, 384)
                assert image.size == size, path


def test_export_json_counts_what_was_written(default_export: Path) -> None:
    summary = json.loads((default_export / "export.json").read_text(encoding="utf-8"))
    samples = read_samples(default_export)
    outputs = [t["value"] for s in samples for t in s["conversations"] if t["from"] == "gpt"]
    expected = {
        "talk": sum(o.startswith("<talk>") for o in outputs),
        "move": sum(PIXEL_OUTPUT.fullmatch(o) is not None for o in outputs),
        "forward": outputs.count("<move>↑"),
        "turn": sum(o.startswith(("<move>←", "<move>→")) for o in outputs),
        "stop": outputs.count("<move>STOP"),
    }
    referenced = {path for s in samples for path in s["images"]}
    on_disk = {p.relative_to(default_export).as_posix() for p in default_export.rglob("*.jpg")}
    counts = summary["counts"]
    assert counts["decisions"] == expected
    assert expected["forward"] >= 1 and expected["move"] >= 5 and expected["talk"] == 6
    assert counts["samples"] == len(samples)
    assert counts["images"] == len(referenced) == len(on_disk)
    assert referenced == on_disk
    assert counts["trajectories"] == 3
    assert summary["settings"] == SftConfig().settings()


def tree(root: Path) -> dict[str, bytes]:
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in root.rglob("*") if p.is_file()}


def test_export_is_deterministic_and_reruns_replace_an_earlier_export(
    hand_dataset: HandDataset, default_export: Path, tmp_path: Path
) -> None:
    out = tmp_path / "again"
    export_sft(hand_dataset.root, out, progress=False)
    assert tree(out) == tree(default_export)
    stale = out / "images" / "stale.jpg"
    stale.write_bytes(b"left over")
    export_sft(hand_dataset.root, out, progress=False)
    assert not stale.exists()
    assert tree(out) == tree(default_export)


def refused_exports(hand_dataset: HandDataset, out: Path, budget: int) -> list[dict[str, Any]]:
    summary = export_sft(hand_dataset.root, out, SftConfig(budget=budget), progress=False)
    asked = [len(d) for d in hand_dataset.dialogs.values()]
    assert summary.refused_questions == sum(max(0, n - budget) for n in asked)
    return read_samples(out)


def test_questions_beyond_the_budget_get_the_refusal(
    hand_dataset: HandDataset, tmp_path: Path
) -> None:
    golden = episode_samples(refused_exports(hand_dataset, tmp_path / "one", 1), 0)
    assert golden[0]["conversations"][2] == human("It is white.")
    assert golden[2]["conversations"][2] == human(REFUSAL_MESSAGE)
    assert (
        "<|navigator|> Is the bathtub in the room on my right? <|oracle|> "
        f"{REFUSAL_MESSAGE}</dialog>" in golden[3]["conversations"][0]["value"]
    )
    none = episode_samples(refused_exports(hand_dataset, tmp_path / "none", 0), 0)
    assert none[0]["conversations"][2] == human(REFUSAL_MESSAGE)


def test_progress_bar_can_be_shown(
    hand_dataset: HandDataset, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    export_sft(hand_dataset.root, tmp_path / "shown", progress=True)
    assert "export-sft" in capsys.readouterr().err
    export_sft(hand_dataset.root, tmp_path / "hidden", progress=False)
    assert "export-sft" not in capsys.readouterr().err
