"""export_sft on a hand-made dataset of real renders: the reference's sampling, conversations
that are exactly what vlln.prompt builds for the same states, the images, and the files."""

from __future__ import annotations

import base64
import json
import math
import shutil
from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from PIL import Image
from tests.datagen.sft.conftest import CATEGORY, HOUSE_SEED, HandDataset
from tests.datagen.sft.samples import episode_samples, read_samples, sample_key
from tests.oracle.llm.chat_server import chat_server, completion

from vlln.agents.model.options import OpenAIVLMOptions, openai_vlm_agent
from vlln.datagen.layout import DOWN_TILT_DEG
from vlln.datagen.reader import HouseDataset
from vlln.datagen.sft import SftConfig, export_sft
from vlln.datagen.sft.records import sharegpt
from vlln.datagen.writer import HouseWriter
from vlln.errors import DataFormatError
from vlln.eval.play import derive_seed
from vlln.prompt import (
    QUESTION_LIMIT_ANSWER,
    Conversation,
    DialogExchange,
    PixelOutput,
    StopOutput,
    TiltDownOutput,
    TurnOutput,
    build_conversation,
    connective_for,
    limit_answers,
    with_look_down,
    with_reply,
)
from vlln.sim.agent import Action, AgentState
from vlln.sim.camera import CameraSpec
from vlln.sim.simulator import Simulator
from vlln.tasks.env import EpisodeInfo
from vlln.tasks.scenes import procedural_scene_id
from vlln.tasks.spec import PixelGoal, TaskType

SEED = 0
DOWN = "125cm_30deg"


def projected_pixel(at: AgentState, later: AgentState) -> tuple[int, int]:
    """Where the feet at ``later`` show on the look-down image taken at ``at``."""
    spec = CameraSpec()
    view = spec.view_matrix(at.position, at.yaw, math.radians(-30.0))
    x, y, z = view[:3, :3] @ np.asarray(later.position) + view[:3, 3]
    fx, fy, cx, cy = spec.intrinsics()
    u, v = cx + fx * x / -z, cy - fy * y / -z
    return math.floor(u + 0.5 + 1e-6), math.floor(v + 0.5 + 1e-6)


def goals_of(hand_dataset: HandDataset, episode: int) -> list[tuple[int, list[int]]]:
    frames = HouseDataset(hand_dataset.root / "trajectories" / hand_dataset.house).frames(episode)
    relative = frames[f"relative_goal_frame_id.{DOWN}"].tolist()
    return list(zip(relative, frames[f"goal.{DOWN}"].tolist(), strict=True))


def expected_move(
    actions: list[Action],
    goals: list[tuple[int, list[int]]],
    frame: int,
    kind: str,
    asked: set[int],
) -> PixelOutput | TurnOutput | StopOutput:
    """The reference's choice: STOP, the pixel goal where there is one, else the turn run,
    which ends before the next frame where questions were asked."""
    if kind == "stop" or actions[frame] == Action.STOP:
        return StopOutput()
    relative, pixel = goals[frame]
    if relative >= 0:
        return PixelOutput(pixel[0], pixel[1])
    run = 1
    while run < 4 and actions[frame + run] == actions[frame] and frame + run not in asked:
        run += 1
    return TurnOutput("left" if actions[frame] == Action.TURN_LEFT else "right", run)


def agent_conversation(
    instruction: str,
    episode_id: str,
    frame: int,
    heard: list[DialogExchange],
    answers_left: int,
    move: PixelOutput | TurnOutput | StopOutput,
) -> Conversation:
    """What an agent sends and answers in this state, through the shared prompt functions,
    with the seed ``vlln eval --seed SEED`` gives the agent of this episode."""
    seed = derive_seed(SEED, "agent", procedural_scene_id(HOUSE_SEED), episode_id)
    conversation = build_conversation(
        instruction,
        frame,
        limit_answers(heard, answers_left),
        connective=connective_for(seed, episode_id, frame),
    )
    if isinstance(move, PixelOutput):
        conversation = with_reply(conversation, TiltDownOutput())
        down = connective_for(seed, episode_id, frame, look_down=True)
        conversation = with_look_down(conversation, frame, connective=down)
    return with_reply(conversation, move)


def test_conversations_are_the_prompt_the_agent_builds(
    hand_dataset: HandDataset, default_export: Path
) -> None:
    """Token for token: each sample equals the prompt functions' conversation for its
    recorded state, with one of the 0..6 answer limits the export may draw."""
    samples = read_samples(default_export)
    checked = 0
    for episode, actions in hand_dataset.actions.items():
        goals = goals_of(hand_dataset, episode)
        exchanges = [DialogExchange(f, q, a) for f, q, a in hand_dataset.dialogs[episode]]
        for sample in episode_samples(samples, episode):
            _, frame, kind = sample_key(sample)
            heard = [
                e for e in exchanges if e.frame < frame or (kind == "dialog" and e.frame == frame)
            ]
            move = expected_move(actions, goals, frame, kind, {e.frame for e in exchanges})
            candidates = [
                agent_conversation(
                    "Search for the bathtub.",
                    hand_dataset.names[episode],
                    frame,
                    heard,
                    left,
                    move,
                )
                for left in range(7)
            ]
            matches = [c for c in candidates if sharegpt(c.turns) == sample["conversations"]]
            assert matches, sample["id"]
            prefix = f"images/{hand_dataset.house}/episode_{episode:06d}"
            paths = [f"{prefix}/{ref.camera}_{ref.frame:06d}.jpg" for ref in matches[0].images]
            assert sample["images"] == paths
            checked += 1
    assert checked == len(samples)


def test_golden_trajectory_is_sampled_as_the_reference_does(default_export: Path) -> None:
    """L L F F F F R S with questions at frames 0 and 6: frame 0 every 4 frames (frame 4 steps
    forward without a visible goal: skipped), STOP x10, both question frames x10."""
    golden = episode_samples(read_samples(default_export), 0)
    assert [sample_key(s)[1:] for s in golden] == (
        [(0, "step")] + [(7, "stop")] * 10 + [(0, "dialog")] * 10 + [(6, "dialog")] * 10
    )
    finals = [s["conversations"][-1]["value"] for s in golden]
    assert finals == ["<move>←←"] + ["<move>STOP"] * 10 + ["<move>←←"] * 10 + ["<move>→"] * 10
    first = golden[11]["conversations"]
    assert first[1] == {"from": "gpt", "value": "<talk>What colour is the bathtub?"}
    assert first[2]["value"] in ("It is white.", QUESTION_LIMIT_ANSWER)
    answers = Counter(s["conversations"][2]["value"] for s in golden[11:21])
    assert set(answers) == {"It is white.", QUESTION_LIMIT_ANSWER}  # drawn limits vary


def test_scan_turn_runs_are_at_most_four(default_export: Path) -> None:
    scan = episode_samples(read_samples(default_export), 2)
    steps = {sample_key(s)[1]: s["conversations"][-1]["value"] for s in scan if "/step/" in s["id"]}
    # frame 8 turns once: the questions at frame 9 are asked before the next turn
    assert steps == {0: "<move>←←←←", 4: "<move>←←←←", 8: "<move>→", 12: "<move>→"}
    dialog = [s["conversations"][-1]["value"] for s in scan if "/dialog/" in s["id"]]
    assert dialog == ["<move>→→"] * 10


def test_pixel_goals_are_where_the_agent_stands_later(
    hand_dataset: HandDataset, default_export: Path
) -> None:
    pixels = 0
    for sample in read_samples(default_export):
        episode, frame, _ = sample_key(sample)
        turns = sample["conversations"]
        if not turns[-1]["value"][6:7].isdigit():
            continue
        assert turns[-3]["value"] == "<move>↓" and turns[-2]["value"].endswith("<image>.")
        col, row = (int(v) for v in turns[-1]["value"].removeprefix("<move>").split())
        relative, _ = goals_of(hand_dataset, episode)[frame]
        states = hand_dataset.states[episode]
        assert (col, row) == projected_pixel(states[frame], states[frame + relative])
        assert sample["images"][-1].endswith(f"/down_{frame:06d}.jpg")
        pixels += 1
    assert pixels >= 2


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
        assert [t["from"] for t in turns] == ["human", "gpt"] * (len(turns) // 2)
        assert sum(turn["value"].count("<image>") for turn in turns) == len(row["images"])
        for path in row["images"]:
            with Image.open(default_export / path) as image:
                assert image.format == "JPEG"
                size = (640, 480) if "/down_" in path else (384, 384)
                assert image.size == size, path


def test_export_json_counts_what_was_written(default_export: Path) -> None:
    summary = json.loads((default_export / "export.json").read_text(encoding="utf-8"))
    samples = read_samples(default_export)
    kinds = Counter(sample_key(s)[2] for s in samples)
    finals = [s["conversations"][-1]["value"] for s in samples if "/step/" in s["id"]]
    referenced = {path for s in samples for path in s["images"]}
    on_disk = {p.relative_to(default_export).as_posix() for p in default_export.rglob("*.jpg")}
    counts = summary["counts"]
    assert counts["samples"] == len(samples)
    assert counts["samples_by_kind"] == {
        "pixel": sum(f[6:7].isdigit() for f in finals),
        "turn": sum(f.startswith(("<move>←", "<move>→")) for f in finals),
        "stop": kinds["stop"],
        "dialog": kinds["dialog"],
    }
    assert kinds["stop"] == 30 and kinds["dialog"] % 10 == 0 and kinds["dialog"] >= 40
    assert counts["images"] == len(referenced) == len(on_disk)
    assert referenced == on_disk
    assert counts["trajectories"] == 3
    assert summary["settings"] == {
        "seed": 0,
        "sample_step": 4,
        "repeats": 10,
        "min_answers": 0,
        "max_answers": 6,
        "history_frames": 8,
        "max_turn_run": 4,
        "forward_steps": False,
    }
    assert SftConfig.from_json(summary["settings"], "export.json") == SftConfig()


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


def test_no_answers_left_means_every_answer_is_the_limit_answer(
    hand_dataset: HandDataset, tmp_path: Path
) -> None:
    export_sft(hand_dataset.root, tmp_path / "none", SftConfig(max_answers=0), progress=False)
    samples = read_samples(tmp_path / "none")
    texts: list[Any] = [t["value"] for s in samples for t in s["conversations"]]
    assert not any("It is white." in text for text in texts)
    dialog = [s for s in samples if "/dialog/" in s["id"]]
    assert all(s["conversations"][2]["value"] == QUESTION_LIMIT_ANSWER for s in dialog)


def test_another_seed_draws_other_limits_and_connectives(
    hand_dataset: HandDataset, default_export: Path, tmp_path: Path
) -> None:
    export_sft(hand_dataset.root, tmp_path / "other", SftConfig(seed=7), progress=False)
    other, default = read_samples(tmp_path / "other"), read_samples(default_export)
    assert [s["id"] for s in other] == [s["id"] for s in default]
    assert [s["conversations"] for s in other] != [s["conversations"] for s in default]


def test_progress_bar_can_be_shown(
    hand_dataset: HandDataset, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    export_sft(hand_dataset.root, tmp_path / "shown", progress=True)
    assert "export-sft" in capsys.readouterr().err
    export_sft(hand_dataset.root, tmp_path / "hidden", progress=False)
    assert "export-sft" not in capsys.readouterr().err


def test_a_folder_in_the_reference_layout_without_info_json_exports_the_same(
    hand_dataset: HandDataset, default_export: Path, tmp_path: Path
) -> None:
    copy = tmp_path / "reference"
    shutil.copytree(hand_dataset.root, copy)
    (copy / "trajectories" / hand_dataset.house / "meta" / "info.json").unlink()
    export_sft(copy, tmp_path / "out", progress=False)
    assert (tmp_path / "out" / "sft.jsonl").read_bytes() == (
        default_export / "sft.jsonl"
    ).read_bytes()


def _sent_images(request: dict[str, Any]) -> list[bytes]:
    """The JPEGs of one chat request, in the order its messages show them."""
    prefix = "data:image/jpeg;base64,"
    return [
        base64.b64decode(part["image_url"]["url"].removeprefix(prefix))
        for message in request["json"]["messages"]
        if isinstance(message["content"], list)
        for part in message["content"]
        if part.get("type") == "image_url"
    ]


def test_the_model_agent_is_shown_the_exported_images_byte_for_byte(
    hand_dataset: HandDataset, default_export: Path, sim: Simulator
) -> None:
    """The openai-vlm agent, standing where a trajectory began, sends its server the very
    bytes training shows for that state: the exported level frame, and the look-down frame as
    stored (the export copies it as it is)."""
    episode = 0
    prefix = f"images/{hand_dataset.house}/episode_{episode:06d}"
    assert any(f"{prefix}/level_000000.jpg" in s["images"] for s in read_samples(default_export))
    start = hand_dataset.states[episode][0]
    tilt = math.radians(DOWN_TILT_DEG)  # pitched down, as the data set renders it
    views = [
        {"rgb": sim.render(AgentState(start.position, start.yaw, pitch)).rgb, "tilt": pitch}
        for pitch in (0.0, tilt)
    ]
    info = EpisodeInfo(
        "golden", TaskType.IIGN, "Search for the bathtub.", CATEGORY,
        sim.config.camera, sim.config.motion, dialog_budget=0, max_steps=50,
    )  # fmt: skip
    script = [completion("<move>↓"), completion("<move>320 240")]
    with chat_server(script) as server:
        options = {"base_url": server.base_url, "model": "images-test", "max_retries": "0"}
        agent = openai_vlm_agent(0, OpenAIVLMOptions.parse("openai-vlm", options))
        agent.reset(info)
        assert agent.act(views[0]) == Action.LOOK_DOWN
        assert isinstance(agent.act(views[1]), PixelGoal)
        requests = list(server.requests)
    level = (default_export / prefix / "level_000000.jpg").read_bytes()
    house = HouseDataset(hand_dataset.root / "trajectories" / hand_dataset.house)
    down = house.image_file("down", episode, 0).read_bytes()
    assert _sent_images(requests[0]) == [level]
    assert _sent_images(requests[1]) == [level, down]


def test_a_dataset_that_kept_no_trajectory_is_refused_before_any_file(
    sim: Simulator, tmp_path: Path
) -> None:
    writer = HouseWriter(tmp_path / "data" / "trajectories", "house_a", sim.config.camera)
    writer.write_rejected("episode-1", "never saw the target")
    writer.finish({})
    with pytest.raises(DataFormatError, match="kept no trajectory, so there is nothing to export"):
        export_sft(tmp_path / "data", tmp_path / "sft", progress=False)
    assert not (tmp_path / "sft").exists()
