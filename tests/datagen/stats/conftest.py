"""A small dataset written through the real writers: the episode stage of the train split's
first house (``build_split``), and its trajectories written by ``HouseWriter`` from walks and
dialogs made here, so every count is known without collecting for minutes."""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import pytest

from vlln.datagen.trajectory import Exchange, Step, Trajectory
from vlln.datagen.writer import HouseWriter
from vlln.prompt.images import stored_frame
from vlln.sim.agent import Action, AgentState
from vlln.sim.camera import CameraSpec
from vlln.sim.renderer import Frame
from vlln.tasks.episode import Episode, read_episodes
from vlln.tasks.generation import EpisodeGenConfig
from vlln.tasks.split_files import build_split, episode_path

CAMERA = CameraSpec(width=8, height=6)  # image content plays no part in the statistics
# (steps, dialog as (trigger, question, answer, question type)) per kept trajectory
Dialog = list[tuple[str, str, str, str]]
KEPT: tuple[tuple[int, Dialog], ...] = (
    (5, []),
    (9, [("attribute", "What colour is the chair?", "It is red.", "attribute")]),
    (
        14,
        [
            ("attribute", "What is it made of?", "Wood.", "attribute"),
            ("route", "Where should I go next?", "Turn left and go forward 3 m.", "route"),
            ("disambiguation", "Is this the one?", "No, it is not.", "disambiguation"),
        ],
    ),
)
REJECTED = ("collision", "target_not_in_final_view", "collision")


@dataclass(frozen=True)
class Dataset:
    root: Path
    finished: str  # house folder names
    unfinished: str


def walk(episode: Episode, steps: int, dialog: Dialog) -> Trajectory:
    """A straight walk along +x in 0.25 m moves, turning once, then STOP."""
    x, y, z = episode.start_position
    actions = [Action.TURN_LEFT] + [Action.MOVE_FORWARD] * (steps - 2) + [Action.STOP]
    moved = [0.0] + [0.25 * k for k in range(steps - 1)]
    trajectory = Trajectory(episode)
    for i, action in enumerate(actions):
        state = AgentState((x + moved[i], y, z), 0.3 if i else 0.0)
        trajectory.steps.append(Step(state, action, False, 10.0 - moved[i]))
    for k, (trigger, question, answer, kind) in enumerate(dialog):
        trajectory.dialog.append(Exchange(k * 2, trigger, question, answer, kind))
    return trajectory


def write_house(
    root: Path, episodes: list[Episode], kept: int, rejected: tuple[str, ...], finish: bool
) -> str:
    writer = HouseWriter(root / "trajectories", episodes[0].scene_id, CAMERA)
    for episode, (steps, dialog) in zip(episodes, KEPT[:kept], strict=False):
        frame = Frame.allocate(CAMERA)
        level = [stored_frame(frame.rgb)] * steps
        writer.write_kept(walk(episode, steps, dialog), level, [frame] * steps)
    for episode, reason in zip(episodes[kept:], rejected, strict=False):
        writer.write_rejected(episode.episode_id, reason)
    if finish:
        writer.finish({"generator": {"made_by": "tests"}})
    return writer.root.name


@pytest.fixture(scope="session")
def dataset(tmp_path_factory: pytest.TempPathFactory) -> Dataset:
    """The episode stage of the train split's first house, as ``vlln data build`` writes it;
    that house finished (3 kept, 3 rejected) and one more in progress (1 kept, 1 rejected)."""
    root = tmp_path_factory.mktemp("dataset")
    config = EpisodeGenConfig(targets_per_house=8)  # the 8 episodes needed, and fast
    build_split("train", 1, root / "episodes", config=config, progress=False)
    episodes = read_episodes(episode_path(root / "episodes", "train", "iign"))
    finished = write_house(root, episodes[:6], 3, REJECTED, finish=True)
    elsewhere = [replace(e, scene_id="vlln/house_99999") for e in episodes[6:8]]
    unfinished = write_house(root, elsewhere, 1, ("collision",), finish=False)
    return Dataset(root, finished, unfinished)
