"""House builds bounded per client and in total; session memory bounded by the scene cache."""

from __future__ import annotations

from typing import Any

import pytest
from fastapi.testclient import TestClient

from vlln.oracle_service.app import create_app
from vlln.oracle_service.config import ServiceConfig
from vlln.oracle_service.hosted_oracle import HostedOracle
from vlln.oracle_service.limits import BuildLimiter
from vlln.oracle_service.schemas import AskRequest, CreateSessionRequest, Pose
from vlln.oracle_service.sessions import ServiceError
from vlln.tasks.scenes import procedural_scene_id

from .conftest import World


def test_limiter_counts_per_client_and_in_total_over_a_minute() -> None:
    now = [0.0]
    limiter = BuildLimiter(per_client=2, total=3, clock=lambda: now[0])
    limiter.admit("a")
    limiter.admit("a")
    with pytest.raises(ServiceError, match="this client's limit of 2") as refused:
        limiter.admit("a")
    assert refused.value.status == 429 and "retry in 60 s" in str(refused.value)
    limiter.admit("b")
    with pytest.raises(ServiceError, match="the server's limit of 3"):
        limiter.admit("c")
    now[0] = 61.0
    limiter.admit("a")  # the window moved on


def test_a_client_cannot_make_the_server_build_house_after_house(world: World) -> None:
    """Reproduction 6: builds are bounded per client."""
    config = ServiceConfig(client_builds_per_minute=1)
    with TestClient(create_app(config)) as client:
        first = {"scene_id": world.scene_id, "target_instance_id": world.target_id}
        assert client.post("/v1/sessions", json=first).status_code == 201
        assert client.post("/v1/sessions", json=first).status_code == 201  # built already
        other = {"scene_id": procedural_scene_id(77), "target_instance_id": 1}
        refused = client.post("/v1/sessions", json=other)
        assert refused.status_code == 429 and "house builds" in refused.json()["error"]


def _ask(hosted: HostedOracle, session_id: str, world: World, question: str) -> Any:
    pose = Pose(**world.poses[1])
    return hosted.ask(session_id, AskRequest(question=question, pose=pose)).answer


def test_sessions_of_dropped_houses_hold_no_simulator_and_answer_alike(world: World) -> None:
    """Reproduction 7: session memory is bounded by the scene cache, not the session count."""
    hosted = HostedOracle(ServiceConfig(scene_capacity=1, oracle_seed=4))
    reference = HostedOracle(ServiceConfig(scene_capacity=1, oracle_seed=4))
    try:
        body = CreateSessionRequest(scene_id=world.scene_id, target_instance_id=world.target_id)
        first = hosted.create(body).session_id
        kept = reference.create(body).session_id
        questions = ["Where is it?", "What colour is it?", "Is this the one?", "Which way?"]
        answers = [_ask(hosted, first, world, questions[0])]
        other = procedural_scene_id(3)
        for instance in range(1, 40):  # a session on another house drops the first house
            try:
                hosted.create(CreateSessionRequest(scene_id=other, target_instance_id=instance))
                break
            except ServiceError:
                continue
        session = hosted.sessions.get(first)
        assert session.oracle is None and session.simulator is None
        answers += [_ask(hosted, first, world, question) for question in questions[1:]]
        expected = [_ask(reference, kept, world, question) for question in questions]
        assert answers == expected  # rebuilt, replayed: the seeded wording goes on
    finally:
        hosted.close()
        reference.close()
