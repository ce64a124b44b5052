"""Collected trajectories: the reference's walk, the dialog triggers and the filter."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from vlln.agents.frontier.frontiers import ChooserConfig
from vlln.datagen.build import BuildConfig, choose_episodes
from vlln.datagen.collector.chooser import BEST, CONTINUE, NEAREST, TargetAwareChooser
from vlln.datagen.collector.collect import CollectorConfig, collect_trajectory
from vlln.datagen.collector.visibility import central_pixels
from vlln.datagen.filtering import (
    COLLISION,
    TARGET_NOT_CENTRED,
    TOO_MANY_TURNS,
    longest_turn_run,
    rejection_reason,
)
from vlln.datagen.trajectory import Step, Trajectory
from vlln.datagen.views import LevelViews
from vlln.oracle.rule_oracle import RuleOracle
from vlln.prompt.images import stored_frame
from vlln.sim.agent import Action, AgentState
from vlln.sim.renderer import Frame
from vlln.sim.simulator import Simulator
from vlln.tasks.episode import Episode, read_episodes
from vlln.tasks.scenes import SceneCache


@pytest.fixture(scope="module")
def house(small_dataset: Path) -> tuple[Simulator, list[Episode]]:
    episodes = read_episodes(small_dataset / "episodes" / "train_iign.json.gz")
    scene_id = episodes[0].scene_id
    cache = SceneCache(capacity=1)
    mine = [e for e in episodes if e.scene_id == scene_id]
    return cache.get(scene_id), choose_episodes(
        mine, BuildConfig(houses=1, per_house=3, preset="small"), 0
    )


# Three walks: the second never finds its target, so a shorter step limit than the default
# 500 keeps the fixture quick; the other two end within it.
WALKS = CollectorConfig(max_steps=250)


@pytest.fixture(scope="module")
def walks(house: tuple[Simulator, list[Episode]]) -> list[Trajectory]:
    sim, episodes = house
    return [collect_trajectory(sim, e, RuleOracle(0), config=WALKS) for e in episodes]


@pytest.mark.slow
def test_walk_starts_with_a_scan_and_ends_with_stop(walks: list[Trajectory]) -> None:
    trajectory = next(walk for walk in walks if walk.failure is None)  # a finished walk
    actions = [s.action for s in trajectory.steps]
    assert actions[:12] == [Action.TURN_LEFT] * 12
    assert actions[-1] == Action.STOP and Action.STOP not in actions[:-1]
    assert Action.LOOK_DOWN not in actions and Action.LOOK_UP not in actions
    for before, after in zip(trajectory.steps, trajectory.steps[1:], strict=False):
        moved = math.dist(before.state.position, after.state.position)
        assert moved <= 0.25 + 1e-9
        if before.action != Action.MOVE_FORWARD:
            assert moved == 0.0
    first = trajectory.dialog[0]
    assert (first.frame_index, first.trigger, first.question_type) == (0, "attribute", "attribute")
    assert [d.frame_index for d in trajectory.dialog] == sorted(
        d.frame_index for d in trajectory.dialog
    )


@pytest.mark.slow
def test_same_seed_same_trajectory(
    house: tuple[Simulator, list[Episode]], walks: list[Trajectory]
) -> None:
    sim, episodes = house  # the walks were collected in order 0, 1, 2: 0 after none
    again = collect_trajectory(sim, episodes[0], RuleOracle(0), config=WALKS)
    assert again.steps == walks[0].steps and again.dialog == walks[0].dialog


@pytest.mark.slow
def test_kept_level_views_are_the_rendered_ones(
    house: tuple[Simulator, list[Episode]], walks: list[Trajectory]
) -> None:
    """The build stores the level views the collector rendered instead of rendering them
    again: they must be those renders, byte for byte, one per step."""
    sim, episodes = house
    views = LevelViews()
    again = collect_trajectory(sim, episodes[0], RuleOracle(0), config=WALKS, on_frame=views.keep)
    assert again.steps == walks[0].steps and len(views.stored) == len(again.steps)
    for index in (0, len(again.steps) // 2, len(again.steps) - 1):
        state = again.steps[index].state
        render = sim.render(AgentState(state.position, state.yaw, 0.0))
        assert views.stored[index] == stored_frame(render.rgb)
    assert np.array_equal(views.last.instance_ids, render.instance_ids)


@pytest.mark.slow
def test_route_questions_follow_progress(walks: list[Trajectory]) -> None:
    """A route question is asked where the agent then walked > 1 m and got closer."""
    for trajectory in walks:
        steps = trajectory.steps
        for turn in (d for d in trajectory.dialog if d.trigger == "route"):
            assert turn.question_type == "route"
            start = steps[turn.frame_index]
            later = steps[turn.frame_index + 1 :]
            walked = np.cumsum(
                [0.0]
                + [
                    math.dist(a.state.position, b.state.position)
                    for a, b in zip(steps[turn.frame_index :], later, strict=False)
                ]
            )
            closer = [s.geodesic_distance < start.geodesic_distance for s in later]
            assert any(w > 1.0 and c for w, c in zip(walked[1:], closer, strict=True))


@pytest.mark.slow
def test_disambiguation_answers_agree_with_the_target(
    house: tuple[Simulator, list[Episode]], walks: list[Trajectory]
) -> None:
    sim, _ = house
    for trajectory in walks:
        episode = trajectory.episode
        target = int(episode.instruction.instance_id[0])
        for turn in (d for d in trajectory.dialog if d.trigger == "disambiguation"):
            frame = sim.render(trajectory.steps[turn.frame_index].state)
            ids = frame.instance_ids
            h, w = ids.shape
            centre = ids[h // 4 : 3 * h // 4, w // 4 : 3 * w // 4]
            same = [
                i
                for i in np.unique(centre)
                if i > 0 and sim.house.instance(int(i)).category == episode.object_category
            ]
            assert same, "asked about a view with no instance of the category in the centre"
            says_yes = turn.answer.lower().startswith("yes")
            shows_target = central_pixels(frame.instance_ids, target) > 0
            assert not says_yes or shows_target


def test_chooser_rules() -> None:
    class Field:
        def distance(self, x: float, z: float, y: float | None = None) -> float:
            return abs(x - 10.0)  # the target lies at x = 10

    chooser = TargetAwareChooser(Field(), (0.0, 0.0))  # type: ignore[arg-type]
    points = np.array([[1.0, 0.0], [5.0, 0.0], [9.0, 0.0]])
    reach = np.array([1.0, 5.0, 9.0])
    always_best = ChooserConfig(p_continue=0.0)
    never_best = ChooserConfig(p_continue=1.0)
    rng = np.random.default_rng(0)
    assert chooser(points, reach, None, rng, always_best) == 0
    assert chooser(points, reach, (4.0, 0.0), rng, always_best) == 2
    assert chooser(points, reach, (4.0, 0.0), rng, never_best) == 1
    assert [c.rule for c in chooser.choices] == [NEAREST, BEST, CONTINUE]
    unreachable = np.array([np.inf, np.inf, np.inf])
    assert chooser(points, unreachable, None, rng, always_best) is None


def _trajectory(
    episode: Episode, sim: Simulator, actions: list[Action], collided: int = -1
) -> Trajectory:
    state = sim.state
    steps = [Step(state, a, i == collided, 1.0) for i, a in enumerate(actions)]
    return Trajectory(episode, steps)


@pytest.mark.slow
def test_filter_reasons(house: tuple[Simulator, list[Episode]], walks: list[Trajectory]) -> None:
    sim, episodes = house
    episode = episodes[0]
    last = walks[0].steps[-1].state
    final = sim.render(last)
    target = int(episode.instruction.instance_id[0])
    blank = Frame(final.rgb, final.depth, np.zeros_like(final.instance_ids))
    scan = [Action.TURN_LEFT] * 12
    forward = [Action.MOVE_FORWARD] * 3
    ok = _trajectory(episode, sim, scan + forward + [Action.STOP])
    shows = Frame(final.rgb, final.depth, np.full_like(final.instance_ids, target))
    assert rejection_reason(ok, (shows,)) is None
    assert rejection_reason(ok, (blank,)) == TARGET_NOT_CENTRED
    assert rejection_reason(ok, (blank, shows)) is None  # either camera will do
    bumped = _trajectory(episode, sim, scan + forward + [Action.STOP], collided=13)
    assert rejection_reason(bumped, (shows,)) == COLLISION
    spinning = _trajectory(episode, sim, scan + forward + [Action.TURN_RIGHT] * 14 + [Action.STOP])
    assert rejection_reason(spinning, (shows,)) == TOO_MANY_TURNS
    thirteen = _trajectory(episode, sim, scan + forward + [Action.TURN_RIGHT] * 13 + [Action.STOP])
    assert rejection_reason(thirteen, (shows,)) is None


def test_longest_turn_run() -> None:
    L, R, F = Action.TURN_LEFT, Action.TURN_RIGHT, Action.MOVE_FORWARD
    assert longest_turn_run([L, L, F, R, L, R, F]) == 3
    assert longest_turn_run([]) == 0


@pytest.mark.slow
def test_an_objectnav_goal_without_view_points_is_left_out(
    small_dataset: Path, house: tuple[Simulator, list[Episode]]
) -> None:
    """ObjectNav episodes list every instance of the category; one with no view point to walk
    to (it happens in about one episode in eight) is no goal of the walk."""
    sim, chosen = house
    episodes = read_episodes(small_dataset / "episodes" / "train_objectnav.json.gz")
    episode = next(e for e in episodes if e.scene_id == chosen[0].scene_id and len(e.goals) > 1)
    emptied = replace(episode.goals[0], view_points=())
    walk = collect_trajectory(
        sim, replace(episode, goals=(emptied, *episode.goals[1:])), RuleOracle(0)
    )
    assert walk.failure is None and walk.steps[-1].action == Action.STOP
    assert walk.target_key != episode.instruction.instance_id[0]
