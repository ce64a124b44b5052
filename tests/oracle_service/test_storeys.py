"""The served oracle in a two-storey house, over real HTTP: sessions by episode and by scene,
poses on the stairs at their tread's height, and route answers that say which way to climb."""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Iterator
from typing import Any

import httpx
import pytest

from tests.stairs import SCENE_ID, Flight, flight_foot, upstairs_episode
from vlln.oracle_service.config import ServiceConfig
from vlln.oracle_service.server import build_server
from vlln.sim.simulator import Simulator
from vlln.sim.viewpoints import storey_view_points
from vlln.tasks.episode import Episode
from vlln.tasks.scenes import SceneCache

from .conftest import TOKEN

START_TIMEOUT = 15.0


@pytest.fixture(scope="module")
def house() -> Iterator[tuple[Simulator, Flight, Episode, int]]:
    """The house, its flight, an episode to a target upstairs and a target downstairs."""
    cache = SceneCache()
    sim = cache.get(SCENE_ID)
    storeys = sim.storeys
    assert storeys is not None
    flight = flight_foot(sim)
    x, y, z = flight.start
    downstairs = next(
        inst.id
        for inst in sorted(sim.house.instances, key=lambda i: i.id)
        if inst.category != "stairs"
        and storeys.level_under(inst.box.min[1]) == 0
        and (points := storey_view_points(storeys, inst.box))
        and math.isfinite(sim.distance_field(points).distance(x, z, y))
    )
    yield sim, flight, upstairs_episode(sim, "upstairs"), downstairs
    cache.close()


@pytest.fixture(scope="module")
def client(house: tuple[Simulator, Flight, Episode, int]) -> Iterator[httpx.Client]:
    config = ServiceConfig(token=TOKEN, episodes=(house[2],))
    server = build_server(config, "127.0.0.1", 0, log_level="warning")
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + START_TIMEOUT
    while not server.started:
        assert thread.is_alive() and time.monotonic() < deadline, "server did not start"
        time.sleep(0.02)
    port = server.servers[0].sockets[0].getsockname()[1]
    headers = {"Authorization": f"Bearer {TOKEN}"}
    with httpx.Client(base_url=f"http://127.0.0.1:{port}", headers=headers, timeout=30.0) as c:
        yield c
    server.should_exit = True
    thread.join(timeout=START_TIMEOUT)


def _ask(client: httpx.Client, session: str, question: str, pose: dict[str, Any]) -> Any:
    response = client.post(f"/v1/sessions/{session}/ask", json={"question": question, "pose": pose})
    assert response.status_code == 200, response.text
    return response.json()


def _pose(point: tuple[float, float, float], yaw: float) -> dict[str, Any]:
    return {"position": list(point), "yaw": yaw, "tilt": 0.0}


@pytest.mark.slow
def test_route_answers_on_the_stairs_say_upstairs_toward_a_target_upstairs(
    client: httpx.Client, house: tuple[Simulator, Flight, Episode, int]
) -> None:
    _, flight, episode, _ = house
    created = client.post("/v1/sessions", json={"episode_id": episode.episode_id})
    assert created.status_code == 201, created.text
    session = created.json()["session_id"]
    heading = _ask(client, session, "Which way should I go?", _pose(flight.start, flight.yaw))
    assert heading["answer"].startswith("It is upstairs, take the stairs."), heading
    assert heading["question_type"] == "route"
    step = _ask(client, session, "What should I do next?", _pose(flight.on_flight, flight.yaw))
    assert step["question_type"] == "route" and "upstairs" in step["answer"], step
    path = _ask(client, session, "Can you give me directions?", _pose(flight.on_flight, flight.yaw))
    assert "go upstairs" in path["answer"].lower(), path


@pytest.mark.slow
def test_route_answers_on_the_stairs_say_downstairs_toward_a_target_downstairs(
    client: httpx.Client, house: tuple[Simulator, Flight, Episode, int]
) -> None:
    sim, flight, _, target = house
    body = {"scene_id": SCENE_ID, "target_instance_id": target, "dialog_budget": 2}
    created = client.post("/v1/sessions", json=body)
    assert created.status_code == 201, created.text
    session = created.json()["session_id"]
    storeys = sim.storeys
    assert storeys is not None
    x, _, z = flight.on_flight
    z_higher = z + (z - flight.start[2]) * 0.8  # further up the flight, on the upper storey
    high = (x, storeys.height_at(1, x, z_higher), z_higher)
    assert storeys.level_of(high[1]) == 1
    facing_down = flight.yaw + math.pi
    step = _ask(client, session, "What should I do next?", _pose(high, facing_down))
    assert step["question_type"] == "route" and "downstairs" in step["answer"], step


@pytest.mark.slow
def test_a_pose_beside_the_treads_height_is_refused_with_the_nearest_point_on_them(
    client: httpx.Client, house: tuple[Simulator, Flight, Episode, int]
) -> None:
    _, flight, episode, _ = house
    session = client.post("/v1/sessions", json={"episode_id": episode.episode_id}).json()
    x, y, z = flight.on_flight
    response = client.post(
        f"/v1/sessions/{session['session_id']}/ask",
        json={"question": "Where is it?", "pose": _pose((x, y + 0.5, z), flight.yaw)},
    )
    assert response.status_code == 422
    detail = response.json()["detail"]
    assert "stairs of storey 0" in detail["message"]
    assert detail["nearest_navigable_point"][1] == pytest.approx(y)
