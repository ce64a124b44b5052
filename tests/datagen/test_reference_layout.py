"""A built dataset read back the way the reference's training code reads it, frame for frame.

The reader below follows the reference's rules (docs/reference-formats.md §3) and knows nothing of
vlln's writer: scene folders with ``meta/episodes.jsonl``, ``data/chunk-XXX/episode_N.parquet``
with ``action`` (element 0 a placeholder; the training actions are ``action[1:] + [0]``),
``pose.125cm_0deg``/``pose.125cm_30deg``, ``goal.125cm_30deg`` and
``relative_goal_frame_id.125cm_30deg``, and JPEG frames under ``videos/chunk-XXX``. What it
reads is compared with the trajectory the collector walks again for the same episode.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pyarrow.parquet as pq
import pytest
from PIL import Image

from tests.datagen.conftest import SMALL
from vlln.datagen.collector.collect import collect_trajectory
from vlln.datagen.trajectory import Trajectory
from vlln.eval.play import episode_seed
from vlln.oracle.rule_oracle import RuleOracle
from vlln.sim.agent import Action, AgentState
from vlln.tasks.episode import read_episodes
from vlln.tasks.scenes import SceneCache

HEIGHT, PITCH_LEVEL, PITCH_DOWN = 125, 0, 30
WIDTH, IMAGE_HEIGHT, HFOV_DEG = 640, 480, 79.0


@dataclass
class ReferenceEpisode:
    """What the reference's annotation loader keeps of one episode."""

    index: int
    instruction: str
    actions: list[int]  # as stored: action[i] led to frame i
    length: int
    poses_level: list[np.ndarray]
    poses_down: list[np.ndarray]
    pixel_goals: list[tuple[int, list[int]]]  # [relative_goal_frame_id, goal]
    dialogs: list[dict[str, Any]]
    row: dict[str, Any]
    video: Path

    def image(self, pitch: int, frame: int) -> Path:
        folder = self.video / f"observation.images.rgb.{HEIGHT}cm_{pitch}deg"
        return folder / f"episode_{self.index:06d}_{frame}.jpg"


def read_reference_scene(scene: Path) -> Iterator[ReferenceEpisode]:
    setting_down = f"{HEIGHT}cm_{PITCH_DOWN}deg"
    setting_level = f"{HEIGHT}cm_{PITCH_LEVEL}deg"
    lines = (scene / "meta" / "episodes.jsonl").read_text().splitlines()
    for row in map(json.loads, lines):
        index = row["episode_index"]
        chunk = f"chunk-{index // 1000:03d}"
        table = pq.read_table(scene / "data" / chunk / f"episode_{index:06d}.parquet")
        columns = {name: table.column(name).to_pylist() for name in table.column_names}
        actions = columns["action"]
        assert len(actions) == row["length"]
        yield ReferenceEpisode(
            index=index,
            instruction=row["tasks"][0].split(";")[0],
            actions=actions,
            length=row["length"],
            poses_level=[np.array(p) for p in columns[f"pose.{setting_level}"]],
            poses_down=[np.array(p) for p in columns[f"pose.{setting_down}"]],
            pixel_goals=[
                (rel, goal)
                for rel, goal in zip(
                    columns[f"relative_goal_frame_id.{setting_down}"],
                    columns[f"goal.{setting_down}"],
                    strict=True,
                )
            ],
            dialogs=row["dialogs"],
            row=row,
            video=scene / "videos" / chunk,
        )


def z_up(point: tuple[float, float, float] | np.ndarray) -> np.ndarray:
    """Habitat (x, y up, z) -> the poses' z-up world (x, -z, y)."""
    x, y, z = (float(v) for v in point)
    return np.array([x, -z, y])


def project(pose: np.ndarray, point: np.ndarray) -> tuple[float, float]:
    """Pixel (col, row) of a z-up world point for an OpenCV camera-to-world ``pose``."""
    local = np.linalg.inv(pose) @ np.append(point, 1.0)
    focal = (WIDTH / 2) / math.tan(math.radians(HFOV_DEG / 2))
    col = focal * local[0] / local[2] + (WIDTH - 1) / 2
    row = focal * local[1] / local[2] + (IMAGE_HEIGHT - 1) / 2
    return col, row


@pytest.fixture(scope="module")
def walked(small_dataset: Path) -> Iterator[list[tuple[ReferenceEpisode, Trajectory, Any]]]:
    """Every kept episode as the reference reads it, the collector's walk of it, and its
    house's simulator (to render the frames again)."""
    by_id = {e.episode_id: e for e in read_episodes(small_dataset / "episodes/train_iign.json.gz")}
    cache = SceneCache(capacity=2)
    found = []
    for scene in sorted((small_dataset / "trajectories").iterdir()):
        for episode in read_reference_scene(scene):
            source = by_id[episode.row["episode_id"]]
            sim = cache.get(source.scene_id)
            oracle = RuleOracle(seed=episode_seed(SMALL.seed, "oracle", source))
            trajectory = collect_trajectory(sim, source, oracle, SMALL.seed, SMALL.collector)
            found.append((episode, trajectory, sim))
    assert found, "the small build kept no trajectory"
    yield found
    cache.close()


@pytest.mark.slow
def test_actions_and_instruction_follow_the_reference_rules(walked: list[Any]) -> None:
    for episode, trajectory, _ in walked:
        assert episode.actions[0] == -1
        training_actions = [*episode.actions[1:], 0]
        assert training_actions == [int(step.action) for step in trajectory.steps]
        assert episode.length == len(trajectory.steps)
        assert episode.instruction == trajectory.episode.instruction.instruction_text
        assert {"episode_index", "tasks", "length", "dialogs"} <= set(episode.row)


@pytest.mark.slow
def test_poses_are_the_cameras_of_every_frame(walked: list[Any]) -> None:
    down = math.radians(PITCH_DOWN)
    for episode, trajectory, _ in walked:
        for frame, step in enumerate(trajectory.steps):
            eye = z_up(step.state.position) + np.array([0.0, 0.0, HEIGHT / 100])
            hx, hz = -math.sin(step.state.yaw), -math.cos(step.state.yaw)  # heading, habitat
            ahead = np.array([hx, -hz, 0.0])
            for pose, pitch in (
                (episode.poses_level[frame], 0.0),
                (episode.poses_down[frame], down),
            ):
                assert pose.shape == (4, 4)
                assert np.allclose(pose[3], [0, 0, 0, 1])
                assert np.allclose(pose[:3, 3], eye, atol=1e-4)
                forward = math.cos(pitch) * ahead + np.array([0.0, 0.0, -math.sin(pitch)])
                assert np.allclose(pose[:3, 2], forward, atol=1e-5)  # OpenCV z: forward
                assert pose[2, 1] < 0  # OpenCV y points down the image
                assert np.linalg.det(pose[:3, :3]) == pytest.approx(1.0, abs=1e-5)


@pytest.mark.slow
def test_pixel_goals_show_where_the_agent_stands_later(walked: list[Any]) -> None:
    goals = 0
    for episode, trajectory, _ in walked:
        steps = trajectory.steps
        asked = {turn.frame_index for turn in trajectory.dialog}
        for frame, (rel, goal) in enumerate(episode.pixel_goals):
            if rel == -1:
                assert goal == [-1, -1]
                continue
            goals += 1
            assert steps[frame].action == Action.MOVE_FORWARD
            assert 1 <= rel <= 8 and frame + rel < len(steps)
            assert not asked & set(range(frame + 1, frame + rel))  # not past a question
            assert steps[frame + rel - 1].action == Action.MOVE_FORWARD
            feet = z_up(steps[frame + rel].state.position)
            col, row = project(episode.poses_down[frame], feet)
            assert abs(col - goal[0]) <= 0.51 and abs(row - goal[1]) <= 0.51
            assert 0 <= goal[0] < WIDTH and 0 <= goal[1] < IMAGE_HEIGHT
    assert goals > 0


@pytest.mark.slow
def test_dialog_indices_map_to_the_frames_questions_were_asked(walked: list[Any]) -> None:
    for episode, trajectory, _ in walked:
        dialogs = episode.dialogs
        assert [d["role"] for d in dialogs] == ["navigator", "oracle"] * len(trajectory.dialog)
        asked = [(t.frame_index, t.question, t.answer) for t in trajectory.dialog]
        pairs = zip(dialogs[::2], dialogs[1::2], strict=True)
        assert [(q["true_idx"], q["message"], a["message"]) for q, a in pairs] == asked
        table = episode.row["path_node_to_frame"]
        for turn in dialogs:
            assert table[turn["nav_idx"]] == turn["true_idx"]
            assert 0 <= turn["true_idx"] < episode.length


@pytest.mark.slow
def test_images_are_the_frames_of_both_cameras(walked: list[Any]) -> None:
    """Each JPEG is its camera's view of its frame: within JPEG noise of a fresh render, and
    nearer to it than to the other camera's view of the same frame unless the two views differ
    by less than the JPEG noise (facing a plain wall close up they look alike)."""
    for episode, trajectory, sim in walked:
        for frame, step in enumerate(trajectory.steps):
            position, yaw = step.state.position, step.state.yaw
            renders = {
                pitch: sim.render(AgentState(position, yaw, -math.radians(pitch))).rgb
                for pitch in (PITCH_LEVEL, PITCH_DOWN)
            }
            for pitch, other in ((PITCH_LEVEL, PITCH_DOWN), (PITCH_DOWN, PITCH_LEVEL)):
                with Image.open(episode.image(pitch, frame)) as image:
                    assert image.format == "JPEG"
                    stored = np.asarray(image.convert("RGB"), np.float64)
                error = np.abs(stored - renders[pitch]).mean()
                assert error < 6.0, (episode.index, frame, pitch)
                # Facing a plain wall the two cameras may see (nearly) the same pixels.
                apart = np.abs(renders[pitch].astype(np.float64) - renders[other]).mean()
                assert apart < 6.0 or error < np.abs(stored - renders[other]).mean()
