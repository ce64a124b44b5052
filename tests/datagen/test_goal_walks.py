"""A built trajectory's pixel goals lead the environment's follower along the teacher's steps.

An agent that makes exactly the decisions the export trains on (pixel goals where the frame
has one, turns and forward steps elsewhere, STOP at the end) plays the trajectory's episode in
:class:`NavigationEnv`; at every frame it must stand where the teacher stood. A goal that the
follower walks on another path (turning where the teacher stepped forward) breaks this: the
model would then see frames that match no training prompt.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from vlln.datagen.layout import reference_pose
from vlln.datagen.reader import HouseDataset, house_folders
from vlln.sim.agent import Action
from vlln.tasks.env import NavigationEnv
from vlln.tasks.episode import read_episodes
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import PixelGoal, TaskConfig, TaskType


@pytest.mark.slow
def test_an_agent_making_the_exported_decisions_walks_the_teachers_path(
    one_house_dataset: Path,
) -> None:
    (folder,) = house_folders(one_house_dataset)
    house = HouseDataset(folder)
    (row,) = house.episodes
    frames = house.frames(int(row["episode_index"]))
    down = house.settings["down"]
    actions = [Action(int(a)) for a in frames["action"][1:]] + [Action.STOP]
    ahead = [int(r) for r in frames[f"relative_goal_frame_id.{down}"]]
    pixels = [(int(g[0]), int(g[1])) for g in frames[f"goal.{down}"]]
    poses = np.asarray(frames[f"pose.{house.settings['level']}"], np.float64)
    assert sum(a >= 0 for a in ahead) >= 3, "too few pixel goals to test"

    (episode,) = [
        e
        for e in read_episodes(one_house_dataset / "episodes" / "train_iign.json.gz")
        if e.episode_id == row["episode_id"]
    ]
    scenes = SceneCache()
    # Questions do not move the agent: the walk is played without dialog.
    env = NavigationEnv([episode], TaskConfig(task=TaskType.IGN), scenes)
    env.reset(options={"episode_index": 0})

    def stands_where_the_teacher_stood(frame: int) -> None:
        state = env.sim.state
        pose = reference_pose(env.sim.config.camera, state.position, state.yaw, 0.0)
        np.testing.assert_allclose(pose, poses[frame], atol=1e-4, err_msg=f"frame {frame}")

    frame, goals_walked = 0, 0
    while actions[frame] != Action.STOP:
        stands_where_the_teacher_stood(frame)
        if ahead[frame] >= 0:
            env.step(Action.LOOK_DOWN)
            observation, *_ = env.step(PixelGoal(*pixels[frame]))
            for _ in range(ahead[frame]):
                assert observation["waypoint_action"] == actions[frame], f"frame {frame}"
                observation, *_ = env.step(actions[frame])
                frame += 1
            assert observation["waypoint_action"] is None, f"the walk goes on at {frame}"
            goals_walked += 1
        else:
            env.step(actions[frame])
            frame += 1
    stands_where_the_teacher_stood(frame)
    assert goals_walked >= 1
    scenes.close()
