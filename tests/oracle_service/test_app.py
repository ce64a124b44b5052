"""The oracle service in-process: sessions, the dialog budget, and every kind of bad request."""

from __future__ import annotations

import json
import math
from collections.abc import Iterator
from typing import Any

import pytest
from fastapi.testclient import TestClient

from vlln.oracle.rule_oracle import RuleOracle
from vlln.oracle_service.app import create_app
from vlln.oracle_service.config import ServiceConfig
from vlln.oracle_service.schemas import MAX_QUESTION_CHARS
from vlln.oracle_service.sessions import REFUSED_TURNS_KEPT
from vlln.sim.agent import AgentState
from vlln.tasks.oracle_protocol import EpisodeContext, Question
from vlln.tasks.spec import REFUSAL_MESSAGE
from vlln.world.frame import yaw_of

from .conftest import TOKEN, World

AUTH = {"Authorization": f"Bearer {TOKEN}"}
MAX_SESSIONS = 3
BODY_LIMIT = 4096


@pytest.fixture(scope="module")
def client(world: World) -> Iterator[TestClient]:
    config = ServiceConfig(
        token=TOKEN,
        episodes=(world.episode,),
        max_sessions=MAX_SESSIONS,
        max_body_bytes=BODY_LIMIT,
        oracle_seed=3,
    )
    with TestClient(create_app(config), headers=AUTH) as test_client:
        yield test_client


def _create(client: TestClient, world: World, **extra: Any) -> dict[str, Any]:
    body = {"scene_id": world.scene_id, "target_instance_id": world.target_id, **extra}
    response = client.post("/v1/sessions", json=body)
    assert response.status_code == 201, response.text
    created: dict[str, Any] = response.json()
    return created


def _ask(client: TestClient, session_id: str, question: str, pose: dict[str, Any]) -> Any:
    return client.post(f"/v1/sessions/{session_id}/ask", json={"question": question, "pose": pose})


def _assert_error(response: Any, status: int) -> dict[str, Any]:
    assert response.status_code == status, response.text
    body: dict[str, Any] = response.json()
    assert set(body) == {"error", "detail"}
    assert body["error"] and body["detail"]
    return body


def test_full_session_answers_then_refuses_past_the_budget(
    client: TestClient, world: World
) -> None:
    created = _create(client, world, dialog_budget=2)
    assert created["target_category"] == world.target_category
    assert created["dialog_budget"] == created["questions_left"] == 2
    sid = created["session_id"]
    pose = world.poses[0]

    first = _ask(client, sid, "What color is it?", pose).json()
    assert first["answered"] and first["question_type"] == "attribute"
    assert world.target_color in first["answer"]
    assert first["questions_left"] == 1
    second = _ask(client, sid, "Which way should I go?", pose).json()
    assert second["answered"] and second["question_type"] == "route"
    third = _ask(client, sid, "What color is it?", pose).json()
    assert third == {
        "answer": REFUSAL_MESSAGE,
        "question_type": "refused",
        "answered": False,
        "questions_left": 0,
        "help_kind": None,
    }

    shown = client.get(f"/v1/sessions/{sid}").json()
    assert [turn["question"] for turn in shown["dialog"]] == [
        "What color is it?",
        "Which way should I go?",
        "What color is it?",
    ]
    assert [turn["answered"] for turn in shown["dialog"]] == [True, True, False]
    assert shown["dialog"][0]["pose"]["position"] == pose["position"]

    assert client.delete(f"/v1/sessions/{sid}").status_code == 204
    _assert_error(client.get(f"/v1/sessions/{sid}"), 404)


def test_questions_past_the_budget_are_counted_but_keep_the_dialog_bounded(
    client: TestClient, world: World
) -> None:
    sid = _create(client, world, dialog_budget=1)["session_id"]
    pose = world.poses[0]
    asked = 1 + 3 * REFUSED_TURNS_KEPT
    replies = [_ask(client, sid, f"Is it number {i}?", pose).json() for i in range(asked)]
    assert [reply["answered"] for reply in replies] == [True] + [False] * (asked - 1)
    shown = client.get(f"/v1/sessions/{sid}").json()
    assert shown["refused_questions"] == asked - 1
    assert [turn["question"] for turn in shown["dialog"]] == [
        f"Is it number {i}?" for i in range(1 + REFUSED_TURNS_KEPT)
    ]
    assert client.delete(f"/v1/sessions/{sid}").status_code == 204


def test_default_budget_is_five(client: TestClient, world: World) -> None:
    assert _create(client, world)["questions_left"] == 5


def _facing_pose_seen_as_the_target(world: World) -> dict[str, Any]:
    """A view point facing the target from which the rule says "yes, this is the one"."""
    sim = world.sim
    target = sim.house.instance(world.target_id)
    probe = RuleOracle()
    probe.start(EpisodeContext(sim, target, tuple(world.view_points)))
    centre = target.box.center
    for x, z in world.view_points[:: max(1, len(world.view_points) // 40)]:
        state = AgentState((x, world.floor_y, z), yaw_of(centre[0] - x, centre[2] - z))
        reply = probe.answer(Question("Is this the one?", state, sim.render(state)))
        if reply.answer.startswith("Yes"):
            return {"position": list(state.position), "yaw": state.yaw}
    raise AssertionError(f"no view point of instance {target.id} sees it centred")


def test_answers_match_the_oracle_in_process(client: TestClient, world: World) -> None:
    """The server renders the view from the pose, so "is this the one?" gets the same answer
    as an agent inside the simulator, and so do all other questions (same seed)."""
    sim = world.sim
    facing = _facing_pose_seen_as_the_target(world)
    turned_away = {**facing, "yaw": facing["yaw"] + math.pi}
    dialog = [
        ("Is this the one?", facing),
        ("Is this the one?", turned_away),
        ("Is this the one?", world.poses[1]),
        ("How do I get there?", world.poses[2]),
        ("Which room is it in?", world.poses[3]),
    ]
    oracle = RuleOracle(seed=3)
    oracle.start(EpisodeContext(sim, sim.house.instance(world.target_id), tuple(world.view_points)))
    sid = _create(client, world, dialog_budget=len(dialog))["session_id"]
    served = []
    for question, pose in dialog:
        px, py, pz = pose["position"]
        state = AgentState((px, py, pz), pose["yaw"], 0.0)
        expected = oracle.answer(Question(question, state, sim.render(state)))
        reply = _ask(client, sid, question, pose).json()
        served.append(reply["answer"])
        assert (reply["answer"], reply["question_type"]) == (
            expected.answer,
            expected.question_type.value,
        )
    assert served[0].startswith("Yes") and served[1].startswith("No")


def test_session_from_an_episode(client: TestClient, world: World) -> None:
    response = client.post("/v1/sessions", json={"episode_id": world.episode.episode_id})
    assert response.status_code == 201
    created = response.json()
    assert created["episode_id"] == world.episode.episode_id
    assert created["instruction"] == world.episode.instruction.instruction_text
    assert created["target_category"] == world.target_category
    answer = _ask(client, created["session_id"], "What color is it?", world.poses[0]).json()
    assert world.target_color in answer["answer"]
    _assert_error(client.post("/v1/sessions", json={"episode_id": "no-such-episode"}), 404)


def test_malformed_json_is_a_client_error_and_the_server_goes_on(
    client: TestClient, world: World
) -> None:
    for body in (b"{not json", b'{"scene_id": "vlln/house_00076",', b"\xff\xfe"):
        response = client.post(
            "/v1/sessions", content=body, headers={"Content-Type": "application/json"}
        )
        assert _assert_error(response, 400)["error"] == "malformed JSON"
    assert _create(client, world)["target_category"] == world.target_category


@pytest.mark.parametrize("content_type", [None, "text/plain", "application/x-www-form-urlencoded"])
def test_bodies_must_be_sent_as_json(
    client: TestClient, world: World, content_type: str | None
) -> None:
    body = json.dumps({"scene_id": world.scene_id, "target_instance_id": world.target_id})
    headers = {} if content_type is None else {"Content-Type": content_type}
    response = client.post("/v1/sessions", content=body.encode(), headers=headers)
    assert "application/json" in _assert_error(response, 415)["detail"]
    with_type = {"Content-Type": "application/json; charset=utf-8"}
    assert client.post("/v1/sessions", content=body.encode(), headers=with_type).status_code == 201


def test_oversized_body_is_413_whether_declared_or_streamed(
    client: TestClient, world: World
) -> None:
    big = json.dumps({"question": "x" * (BODY_LIMIT + 10), "pose": world.poses[0]}).encode()
    sid = _create(client, world)["session_id"]
    declared = client.post(
        f"/v1/sessions/{sid}/ask", content=big, headers={"Content-Type": "application/json"}
    )
    _assert_error(declared, 413)

    def chunks() -> Iterator[bytes]:
        for start in range(0, len(big), 1000):
            yield big[start : start + 1000]

    streamed = client.post(
        f"/v1/sessions/{sid}/ask", content=chunks(), headers={"Content-Type": "application/json"}
    )
    _assert_error(streamed, 413)
    assert _ask(client, sid, "What color is it?", world.poses[0]).status_code == 200


@pytest.mark.parametrize("header", ["", "Bearer wrong-token", f"Basic {TOKEN}", "Bearer"])
def test_missing_or_bad_token_is_401(client: TestClient, world: World, header: str) -> None:
    headers = {"Authorization": header}
    response = client.post("/v1/sessions", json={"episode_id": "ep-1"}, headers=headers)
    assert _assert_error(response, 401)["error"] == "unauthorized"
    assert response.headers["WWW-Authenticate"] == "Bearer"
    # not even malformed bodies are parsed without the token
    _assert_error(client.post("/v1/sessions", content=b"{", headers=headers), 401)
    # health stays open, for liveness probes
    health = client.get("/v1/health", headers=headers)
    assert health.status_code == 200 and health.json()["status"] == "ok"


def test_unknown_session_is_404_everywhere(client: TestClient, world: World) -> None:
    ask = {"question": "What color is it?", "pose": world.poses[0]}
    _assert_error(client.post("/v1/sessions/nope/ask", json=ask), 404)
    _assert_error(client.get("/v1/sessions/nope"), 404)
    _assert_error(client.delete("/v1/sessions/nope"), 404)
    _assert_error(client.get("/v1/no-such-endpoint"), 404)


def test_pose_off_the_floor_is_422_naming_the_nearest_navigable_point(
    client: TestClient, world: World
) -> None:
    sid = _create(client, world)["session_id"]
    x, _, z = world.poses[0]["position"]
    inside_wall = {"position": [x + 500.0, world.floor_y, z], "yaw": 0.0}
    body = _assert_error(_ask(client, sid, "What color is it?", inside_wall), 422)
    nearest = body["detail"]["nearest_navigable_point"]
    assert world.sim.grid.is_navigable(nearest[0], nearest[2])
    assert _ask(client, sid, "What color is it?", {"position": nearest, "yaw": 0.0}).is_success
    flying = {"position": [x, world.floor_y + 2.0, z], "yaw": 0.0}
    _assert_error(_ask(client, sid, "What color is it?", flying), 422)
    too_tilted = {"position": [x, world.floor_y, z], "yaw": 0.0, "tilt": math.radians(80.0)}
    _assert_error(_ask(client, sid, "What color is it?", too_tilted), 422)
    # refused questions did not count: the budget is untouched by rejected requests
    assert client.get(f"/v1/sessions/{sid}").json()["questions_left"] == 4


@pytest.mark.parametrize(
    "body",
    [
        {"scene_id": "vlln/house_00076", "target_instance_id": 1, "colour": "red"},
        {"scene_id": "vlln/house_00076", "target_instance_id": "1"},
        {"scene_id": "vlln/house_00076"},
        {"scene_id": "vlln/house_00076", "target_instance_id": 1, "episode_id": "ep-1"},
        {"scene_id": "vlln/house_00076", "target_instance_id": 1, "dialog_budget": -1},
        {"scene_id": "x" * 500, "target_instance_id": 1},
        [],
    ],
)
def test_invalid_session_requests_are_422(client: TestClient, body: Any) -> None:
    detail = _assert_error(client.post("/v1/sessions", json=body), 422)["detail"]
    assert all({"field", "problem"} <= set(problem) for problem in detail)


@pytest.mark.parametrize(
    "change",
    [
        {"extra": 1},
        {"question": ""},
        {"question": "?" * (MAX_QUESTION_CHARS + 1)},
        {"pose": {"position": [0.0, 0.0, 0.0], "yaw": 0.0, "roll": 0.0}},
        {"pose": {"position": [0.0, 0.0], "yaw": 0.0}},
        {"pose": {"position": [0.0, 0.0, "1"], "yaw": 0.0}},
        {"pose": {"position": [0.0, 0.0, 1e300], "yaw": 0.0}},
    ],
)
def test_invalid_questions_are_422(client: TestClient, world: World, change: Any) -> None:
    sid = _create(client, world)["session_id"]
    body = {"question": "What color is it?", "pose": world.poses[0], **change}
    _assert_error(client.post(f"/v1/sessions/{sid}/ask", json=body), 422)


def test_non_finite_numbers_are_422(client: TestClient, world: World) -> None:
    sid = _create(client, world)["session_id"]
    x, y, _ = world.poses[0]["position"]
    raw = f'{{"question": "Where?", "pose": {{"position": [{x}, {y}, NaN], "yaw": 0}}}}'
    response = client.post(
        f"/v1/sessions/{sid}/ask", content=raw, headers={"Content-Type": "application/json"}
    )
    _assert_error(response, 422)


def test_unknown_scene_and_instance_are_404_with_the_valid_form(
    client: TestClient, world: World
) -> None:
    scene = client.post("/v1/sessions", json={"scene_id": "mp3d/abc", "target_instance_id": 1})
    assert "vlln/house_<seed>" in _assert_error(scene, 404)["detail"]
    missing = max(world.instance_ids) + 1
    instance = client.post(
        "/v1/sessions", json={"scene_id": world.scene_id, "target_instance_id": missing}
    )
    assert str(missing) in _assert_error(instance, 404)["detail"]


def test_store_keeps_only_the_most_recently_used_sessions(client: TestClient, world: World) -> None:
    first = _create(client, world)["session_id"]
    second = _create(client, world)["session_id"]
    for _ in range(MAX_SESSIONS - 2):
        _create(client, world)
    assert client.get(f"/v1/sessions/{first}").status_code == 200  # now most recently used
    newest = _create(client, world)["session_id"]
    _assert_error(client.get(f"/v1/sessions/{second}"), 404)
    assert client.get(f"/v1/sessions/{first}").status_code == 200
    assert client.get(f"/v1/sessions/{newest}").status_code == 200
    assert client.get("/v1/health").json()["sessions"] == MAX_SESSIONS


@pytest.mark.parametrize(
    "alias",
    [
        "vlln/house_76",
        "vlln/house_076",
        "vlln/house_\u0660\u0660\u0660\u0667\u0666",
        "vlln/house_" + "9" * 40,
    ],
)
def test_scene_ids_have_one_spelling(client: TestClient, world: World, alias: str) -> None:
    """Reproduction 6: aliases of a house and unbounded seeds are not other scenes."""
    response = client.post("/v1/sessions", json={"scene_id": alias, "target_instance_id": 1})
    detail = _assert_error(response, 404)["detail"]
    assert "vlln/house_00076" in detail or "at most" in detail


def test_docs_and_schema_are_served(client: TestClient) -> None:
    """Reproduction 11."""
    docs = client.get("/docs", headers={"Authorization": ""})
    assert docs.status_code == 200 and "swagger" in docs.text.lower()
    schema = client.get("/v1/openapi.json", headers={"Authorization": ""}).json()
    assert "/v1/sessions/{session_id}/ask" in schema["paths"]
