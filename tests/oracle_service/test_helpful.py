"""Sessions created with ``"oracle": "helpful"``: questions beyond the paper's get grounded
answers over HTTP, the same as the helpful oracle's in process; the default stays the rule
oracle."""

from __future__ import annotations

from typing import Any

from fastapi.testclient import TestClient

from vlln.oracle.helpful.oracle import HelpfulOracle
from vlln.oracle.route import CANNOT_ANSWER
from vlln.oracle.rule_oracle import RuleOracle
from vlln.sim.agent import AgentState
from vlln.tasks.oracle_protocol import EpisodeContext, Oracle, Question

from .conftest import World
from .test_app import _ask, _create, _facing_pose_seen_as_the_target, client

__all__ = ["client"]  # the service of test_app, seed 3

BEYOND_THE_PAPER = (
    "Are you sure?",
    "is it the one on the left or the one on the right?",
    "should I go upstairs?",
    "is it near a window?",
    "I think I'm lost, can you help?",
)


def _dialog(world: World) -> list[tuple[str, dict[str, Any]]]:
    facing = _facing_pose_seen_as_the_target(world)
    poses = [facing, facing, *world.poses[1:4]]
    return list(zip(BEYOND_THE_PAPER, poses, strict=True))


def _in_process(
    oracle: Oracle, world: World, dialog: list[tuple[str, dict[str, Any]]]
) -> list[str]:
    """The answers of ``oracle`` asked the dialog in process, each with the poses so far."""
    sim = world.sim
    oracle.start(EpisodeContext(sim, sim.house.instance(world.target_id), tuple(world.view_points)))
    answers, walked = [], []
    for question, pose in dialog:
        state = AgentState(tuple(pose["position"]), pose["yaw"], 0.0)
        walked.append(state.position)
        answers.append(
            oracle.answer(Question(question, state, sim.render(state), tuple(walked))).answer
        )
    return answers


def _served(
    client: TestClient, world: World, dialog: list[tuple[str, dict[str, Any]]], **extra: Any
) -> list[dict[str, Any]]:
    sid = _create(client, world, dialog_budget=len(dialog), **extra)["session_id"]
    return [_ask(client, sid, question, pose).json() for question, pose in dialog]


def test_a_helpful_session_answers_questions_beyond_the_papers(
    client: TestClient, world: World
) -> None:
    dialog = _dialog(world)
    replies = _served(client, world, dialog, oracle="helpful")
    assert all(reply["answered"] for reply in replies)
    answers = [reply["answer"] for reply in replies]
    assert CANNOT_ANSWER not in answers
    assert answers == _in_process(HelpfulOracle(RuleOracle(3)), world, dialog)
    sure, side, upstairs, window, lost = answers
    assert sure.startswith(("Yes, I am sure", "I can't tell which one"))
    assert "the one" in side and replies[1]["question_type"] == "disambiguation"
    assert upstairs == "No. This house has one floor, and it is on it."
    assert window.startswith(("Yes, it is near a window", "No, the nearest window", "No, I know"))
    assert lost.startswith("You are in the ") and "From here: " in lost
    kinds = [reply["help_kind"] for reply in replies]
    assert kinds == ["confirmation", "comparison", "floor", "window", "reroute"]
    sid = _create(client, world, dialog_budget=1, oracle="helpful")["session_id"]
    _ask(client, sid, *dialog[0])
    turns = client.get(f"/v1/sessions/{sid}").json()["dialog"]
    assert [turn["help_kind"] for turn in turns] == ["confirmation"]


def test_the_default_session_keeps_the_rule_oracles_answers(
    client: TestClient, world: World
) -> None:
    dialog = _dialog(world)
    answers = [reply["answer"] for reply in _served(client, world, dialog)]
    assert answers == _in_process(RuleOracle(3), world, dialog)
    assert answers[0] == CANNOT_ANSWER  # "Are you sure?" is no question of the paper's
    assert answers == [reply["answer"] for reply in _served(client, world, dialog, oracle="rules")]
    assert {reply["help_kind"] for reply in _served(client, world, dialog)} == {None}


def test_an_unknown_oracle_is_refused(client: TestClient, world: World) -> None:
    body = {"scene_id": world.scene_id, "target_instance_id": world.target_id, "oracle": "llm"}
    response = client.post("/v1/sessions", json=body)
    assert response.status_code == 422 and "oracle" in response.text
