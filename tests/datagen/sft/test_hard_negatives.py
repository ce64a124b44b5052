"""``--hard-negatives``: samples at frames where a same-category distractor is in plain view.

A hand-made IIGN trajectory in a real house: the agent stands facing one instance of a
category the house holds several of, the target being another one; it asks a question, turns
a full circle (so the STOP frame faces the distractor again) and stops. Which frames show the
distractor is decided here by rendering the recorded states again, independently of the
export's reading of the stored poses.
"""

from __future__ import annotations

import json
import math
import shutil
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from tests.datagen.sft.conftest import HOUSE_SEED, level_views, walk
from tests.datagen.sft.samples import read_samples, sample_key

from vlln.bench.learning import teacher_decisions
from vlln.datagen.build import BuildConfig, check_settings
from vlln.datagen.collector.visibility import central_pixels
from vlln.datagen.layout import TRAJECTORIES_DIR, level_state, reference_pose
from vlln.datagen.sft import SftConfig, export_sft
from vlln.datagen.sft.distractors import DISTRACTOR_PIXELS
from vlln.datagen.views import down_views, final_down_view
from vlln.datagen.writer import HouseWriter
from vlln.errors import ConfigError
from vlln.prompt import StopOutput, format_output
from vlln.sim.agent import Action, AgentState
from vlln.sim.camera import CameraSpec
from vlln.sim.simulator import Simulator
from vlln.tasks.scenes import procedural_scene_id
from vlln.world.frame import wrap_angle, yaw_of

QUESTION = "Is this the one you mean?"
TURNS = 12  # a full circle of 30° turns


@dataclass(frozen=True)
class DistractorCase:
    root: Path
    states: list[AgentState]  # by frame
    target: int
    others: list[int]  # the other instances of the target's category


def facing_a_distractor(sim: Simulator) -> tuple[AgentState, int, list[int], str]:
    """A state facing an instance of a category the house holds several of, showing it in
    plain view and more than another instance of the category, which is then the target."""
    house = sim.house
    floor_y = sim.state.position[1]
    cells = sim.grid.free_cells()
    points = np.array([sim.grid.cell_to_world(int(r), int(c)) for r, c in cells[::7]])
    for category in sorted({i.category for i in house.instances}):
        ids = [i.id for i in house.instances_of(category)]
        for instance in house.instances_of(category)[: 2 if len(ids) > 1 else 0]:
            cx, _, cz = instance.box.center
            near = np.hypot(points[:, 0] - cx, points[:, 1] - cz)
            for x, z in points[(near > 1.0) & (near < 2.5)][:6]:
                state = AgentState((float(x), floor_y, float(z)), yaw_of(cx - x, cz - z), 0.0)
                view = sim.render_instance_ids(state)
                pixels = {i: central_pixels(view, i) for i in ids}
                target = min(pixels, key=lambda i: pixels[i])
                if pixels[instance.id] >= max(DISTRACTOR_PIXELS, pixels[target] + 1):
                    return state, target, [i for i in ids if i != target], category
    raise AssertionError("no instance of a repeated category in plain view in the test house")


@pytest.fixture(scope="module")
def case(sim: Simulator, tmp_path_factory: pytest.TempPathFactory) -> DistractorCase:
    start, target, others, category = facing_a_distractor(sim)
    root = tmp_path_factory.mktemp("distractors")
    check_settings(root, BuildConfig(houses=1, preset="small"))  # an IIGN build.json
    actions = [Action.TURN_LEFT] * TURNS + [Action.STOP]
    dialog = [(0, QUESTION, "No, the one I mean is elsewhere.")]
    trajectory = walk(sim, "circle", start, actions, dialog, category, str(target))
    writer = HouseWriter(
        root / TRAJECTORIES_DIR, procedural_scene_id(HOUSE_SEED), sim.config.camera
    )
    last_down = final_down_view(sim, trajectory)
    writer.write_kept(
        trajectory, level_views(sim, trajectory), down_views(sim, trajectory, last_down)
    )
    writer.finish({})
    return DistractorCase(root, [s.state for s in trajectory.steps], target, others)


def shows_distractor(sim: Simulator, case: DistractorCase, frame: int) -> bool:
    view = sim.render_instance_ids(case.states[frame])
    target = central_pixels(view, case.target)
    pixels = [central_pixels(view, other) for other in case.others]
    return any(p >= DISTRACTOR_PIXELS and p > target for p in pixels)


def test_hard_negatives_are_the_frames_that_show_a_distractor_and_never_the_stop(
    sim: Simulator, case: DistractorCase, tmp_path: Path
) -> None:
    config = SftConfig(hard_negatives=3)
    export_sft(case.root, tmp_path, config, progress=False)
    samples = read_samples(tmp_path)
    negatives = [s for s in samples if sample_key(s)[2] == "negative"]
    frames = [sample_key(s)[1] for s in negatives]
    shown = {f for f in range(TURNS + 1) if shows_distractor(sim, case, f)}
    assert TURNS in shown  # the STOP frame faces the distractor too, yet is no negative
    assert set(frames) == shown - {TURNS} and 0 in frames
    assert all(frames.count(f) == config.hard_negatives for f in set(frames))
    stop = format_output(StopOutput())
    assert all(s["conversations"][-1]["value"] != stop for s in negatives)
    at_question = {
        (
            sample_key(s)[2],
            any(t["from"] == "gpt" and QUESTION in t["value"] for t in s["conversations"]),
        )
        for s in samples
        if sample_key(s)[1] == 0
    }
    # At the question frame the negative asks first, as the dialog sample does; the step not.
    assert at_question == {("step", False), ("dialog", True), ("negative", True)}
    counts = json.loads((tmp_path / "export.json").read_text())["counts"]
    assert counts["samples_by_kind"]["negative"] == len(negatives) > 0
    assert counts["samples"] == len(samples)


def test_without_the_flag_the_export_is_the_one_with_it_less_its_negatives(
    case: DistractorCase, tmp_path: Path
) -> None:
    export_sft(case.root, tmp_path / "off", progress=False)
    export_sft(case.root, tmp_path / "on", SftConfig(hard_negatives=3), progress=False)
    off = (tmp_path / "off" / "sft.jsonl").read_text().splitlines()
    on = (tmp_path / "on" / "sft.jsonl").read_text().splitlines()
    assert off == [line for line in on if "/negative/" not in line] != on
    documents = [json.loads((tmp_path / d / "export.json").read_text()) for d in ("off", "on")]
    assert "hard_negatives" not in documents[0]["settings"]
    assert "negative" not in documents[0]["counts"]["samples_by_kind"]
    assert documents[1]["settings"]["hard_negatives"] == 3
    # The agreement benchmark scores both on the reference's decisions alone.
    decisions = {
        name: [(d.turns, [p.relative_to(tmp_path / name) for p in d.images], d.answer)
               for d in teacher_decisions(tmp_path / name)]
        for name in ("on", "off")
    }  # fmt: skip
    assert decisions["on"] == decisions["off"]


def test_objectnav_has_no_distractors_and_a_dataset_of_unknown_task_is_refused(
    case: DistractorCase, tmp_path: Path
) -> None:
    objectnav, unknown = tmp_path / "objectnav", tmp_path / "unknown"
    for root in (objectnav, unknown):
        shutil.copytree(case.root / TRAJECTORIES_DIR, root / TRAJECTORIES_DIR)
    check_settings(objectnav, BuildConfig(houses=1, preset="small", task="objectnav"))
    config = SftConfig(hard_negatives=3)
    summary = export_sft(objectnav, tmp_path / "out", config, progress=False)
    assert summary.by_kind["negative"] == 0 and summary.samples > 0
    with pytest.raises(ConfigError, match=r"build\.json"):  # no build.json: the task is unknown
        export_sft(unknown, tmp_path / "refused", config, progress=False)


def test_a_stored_level_pose_gives_back_the_state_it_was_rendered_from() -> None:
    spec = CameraSpec()
    rng = np.random.default_rng(0)
    for _ in range(20):
        position = (float(rng.uniform(-9, 9)), float(rng.uniform(0, 6)), float(rng.uniform(-9, 9)))
        yaw = float(rng.uniform(-3 * math.pi, 3 * math.pi))
        pose = reference_pose(spec, position, yaw, 0.0).astype(np.float32)  # as stored
        state = level_state(spec, pose)
        np.testing.assert_allclose(state.position, position, atol=1e-5)
        assert abs(wrap_angle(state.yaw - yaw)) < 1e-5 and state.tilt == 0.0
