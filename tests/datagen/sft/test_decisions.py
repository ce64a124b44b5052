"""Cutting trajectories into decisions: turn runs, questions, the forward fallback."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from tests.datagen.sft.conftest import HandDataset
from tests.datagen.sft.samples import episode_samples, final_outputs, read_samples

from vlln.datagen.sft import SftConfig, export_sft
from vlln.datagen.sft.decisions import (
    Decision,
    ForwardStep,
    PixelGoal,
    Stop,
    TurnRun,
    cut_decisions,
)
from vlln.datagen.sft.dialog import DialogExchange
from vlln.datagen.sft.pixel_goals import Pixel
from vlln.errors import DataFormatError
from vlln.sim.agent import Action
from vlln.sim.camera import CameraSpec

L, R, F, S = Action.TURN_LEFT, Action.TURN_RIGHT, Action.MOVE_FORWARD, Action.STOP


def never_asked(frame: int, later: int) -> Pixel | None:
    raise AssertionError(f"no forward step, yet a goal was looked up at frame {frame}")


def turns_only(actions: list[Action], questions: list[int], run: int = 6) -> list[Decision]:
    exchanges = [DialogExchange(f, f"question {f}", f"answer {f}") for f in questions]
    feet = np.zeros((len(actions), 3))
    return cut_decisions(actions, feet, exchanges, never_asked, max_turn_run=run)


def test_turn_runs_are_capped_and_split_by_direction() -> None:
    decisions = turns_only([L] * 14 + [R] * 2 + [S], [])
    moves = [d.move for d in decisions]
    assert moves == [TurnRun(L, 6), TurnRun(L, 6), TurnRun(L, 2), TurnRun(R, 2), Stop()]
    assert [d.frame for d in decisions] == [0, 6, 12, 14, 16]
    assert [d.move for d in turns_only([L] * 7 + [S], [], run=3)] == [
        TurnRun(L, 3),
        TurnRun(L, 3),
        TurnRun(L, 1),
        Stop(),
    ]


def test_a_question_ends_a_run_and_is_asked_at_its_frame() -> None:
    decisions = turns_only([L] * 8 + [S], [0, 3, 3, 8])
    assert [(d.frame, d.move) for d in decisions] == [
        (0, TurnRun(L, 3)),
        (3, TurnRun(L, 5)),
        (8, Stop()),
    ]
    assert [[t.question for t in d.talks] for d in decisions] == [
        ["question 0"],
        ["question 3", "question 3"],
        ["question 8"],
    ]


def test_bad_action_sequences_are_refused() -> None:
    with pytest.raises(DataFormatError, match="last action"):
        turns_only([L, L], [])
    with pytest.raises(DataFormatError, match="only the last action may be STOP"):
        turns_only([L, S, L, S], [])
    with pytest.raises(DataFormatError, match="not MOVE_FORWARD"):
        turns_only([L, Action.LOOK_DOWN, S], [])
    with pytest.raises(DataFormatError, match=r"outside frames 0\.\.2"):
        turns_only([L, L, S], [3])


def test_scan_trajectory_outputs(hand_dataset: HandDataset, default_export: Path) -> None:
    scan = episode_samples(read_samples(default_export), 2)
    assert final_outputs(scan) == [
        "<move>←←←←←←",
        "<move>←←",
        "<move>→",  # the question at frame 9 ends the right-turn run
        "<move>→→",
        "<move>↑",
        "<move>→",
        "<move>STOP",
    ]
    assert scan[3]["conversations"][1]["value"] == "<talk>Which way is the bathtub?"


def test_max_turn_run_setting(hand_dataset: HandDataset, tmp_path: Path) -> None:
    export_sft(hand_dataset.root, tmp_path, SftConfig(max_turn_run=3), progress=False)
    scan = episode_samples(read_samples(tmp_path), 2)
    assert final_outputs(scan)[:4] == ["<move>←←←", "<move>←←←", "<move>←←", "<move>→"]


def test_a_step_too_short_to_show_falls_back_to_a_forward_step(
    hand_dataset: HandDataset,
) -> None:
    """The scan's one forward step lands 0.25 m ahead, below the look-down image's bottom
    row, and is followed by a turn and STOP: no pixel goal can stand for it."""
    states = hand_dataset.states[2]
    at, later = states[11], states[12]
    spec = CameraSpec()
    view = spec.view_matrix(at.position, at.yaw, math.radians(-30.0))
    _, y, z = view[:3, :3] @ np.asarray(later.position) + view[:3, 3]
    _, fy, _, cy = spec.intrinsics()
    assert cy - fy * y / -z > spec.height  # below the image
    actions = [L] * 8 + [R] * 3 + [F, R, S]
    feet = np.array([s.position for s in states])
    looked_up: list[tuple[int, int]] = []

    def locate(frame: int, goal: int) -> Pixel | None:
        looked_up.append((frame, goal))
        return None

    decisions = cut_decisions(actions, feet, [], locate)
    assert decisions[-3].move == ForwardStep() and decisions[-3].frame == 11
    assert decisions[-2].frame == 12
    assert looked_up == [(11, 12)]


def test_pixel_goal_takes_the_farthest_shown_arrival_before_the_next_question() -> None:
    """Turns after the last forward step are not part of a goal; a question caps it."""
    actions = [F, F, L, F, R, R, F, F, F, F, F, F, S]
    feet = np.array([[0.0, 0.0, -0.25 * i] for i in range(len(actions))])
    shown = {4, 6, 10}  # frames whose feet "show" on frame 0's look-down image

    def locate(frame: int, goal: int) -> Pixel | None:
        return (goal, frame) if frame == 0 and goal in shown else None

    first = cut_decisions(actions, feet, [], locate)[0]
    # 10 is beyond 8 steps, 6 was reached by a turn, not a forward step: 4 is the goal.
    assert first.move == PixelGoal(4, 0, 4)
    asked = [DialogExchange(3, "q", "a")]
    capped = cut_decisions(actions, feet, asked, locate)[0]
    assert capped.move == ForwardStep()  # frame 4 lies beyond the question at frame 3
