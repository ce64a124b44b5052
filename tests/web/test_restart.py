"""Killing the server mid-episode loses nothing: finished episodes stay recorded once, a
person's episode in flight resumes with the same code, an agent's is recorded as abandoned."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import httpx
import pytest

from vlln.eval.results import load_run_records
from vlln.tasks.metrics import success

from .conftest import Study

NAMES = {
    "MOVE_FORWARD": "forward",
    "TURN_LEFT": "left",
    "TURN_RIGHT": "right",
    "STOP": "stop",
}


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


def _launch(study: Study, out: Path, port: int) -> subprocess.Popen[bytes]:
    command = [sys.executable, "-m", "vlln.cli", "serve", "web"]
    command += ["--episode-file", str(study.episode_file), "--out", str(out), "--port", str(port)]
    process = subprocess.Popen(command, env=dict(os.environ), stderr=subprocess.PIPE)
    deadline = time.monotonic() + 60.0
    while True:
        assert process.poll() is None, process.stderr.read().decode() if process.stderr else ""
        try:
            if httpx.get(f"http://127.0.0.1:{port}/api/health").status_code == 200:
                return process
        except httpx.TransportError:
            pass
        assert time.monotonic() < deadline, "the server did not start"
        time.sleep(0.1)


def _until(client: httpx.Client, path: str, code: str, done: object) -> dict[str, object]:
    view: dict[str, object] = {"version": 0}
    for _ in range(100):
        view = client.get(
            f"{path}?after={view['version']}", headers={"X-Session-Code": code}
        ).json()
        if done(view):  # type: ignore[operator]
            return view
    raise AssertionError(f"{path} never reached the wanted state: {view.get('status')}")


def _play(client: httpx.Client, code: str, actions: list[str]) -> dict[str, object]:
    view: dict[str, object] = {}
    for action in actions:
        reply = client.post(
            "/api/navigator/act", json={"action": NAMES[action]}, headers={"X-Session-Code": code}
        )
        assert reply.status_code == 200, reply.text
        view = reply.json()
    return view


@pytest.mark.slow
def test_a_killed_server_resumes_people_and_records_agents_as_abandoned(
    study: Study, tmp_path: Path
) -> None:
    out, port = tmp_path / "study", _free_port()
    server = _launch(study, out, port)
    url = f"http://127.0.0.1:{port}"
    try:
        with httpx.Client(base_url=url, timeout=30.0) as client:

            def create(
                navigator: str, participant: str, oracle: str, episode: int
            ) -> dict[str, str]:
                body = {"navigator": navigator, "participant": participant, "oracle": oracle}
                reply = client.post("/api/sessions", json={**body, "episode_index": episode})
                assert reply.status_code == 201, reply.text
                return reply.json()  # type: ignore[no-any-return]

            playing = lambda view: view["status"] == "playing"  # noqa: E731
            done = create("human", "p10", "rules", 0)["navigator_code"]
            _until(client, "/api/navigator", done, playing)
            assert _play(client, done, study.routes[0])["result"] is not None
            flying = create("human", "p11", "rules", 1)["navigator_code"]
            _until(client, "/api/navigator", flying, playing)
            _play(client, flying, study.routes[1][:3])
            asked = client.post(
                "/api/navigator/ask",
                json={"question": "What color is it?"},
                headers={"X-Session-Code": flying},
            ).json()
            assert asked["dialog"][0]["answered"]
            helper = create("frontier", "x", "human", 2)["oracle_code"]
            _until(client, "/api/oracle", helper, lambda view: view["question"] is not None)
    finally:
        server.send_signal(signal.SIGKILL)
        server.wait()

    assert [r.agent for r in load_run_records([out])] == ["human:p10"]
    server = _launch(study, out, port)
    try:
        with httpx.Client(base_url=url, timeout=30.0) as client:
            view = _until(client, "/api/navigator", flying, lambda v: v["status"] == "playing")
            assert view["steps"] == 3 and len(view["dialog"]) == 1  # type: ignore[arg-type]
            assert _play(client, flying, study.routes[1][3:])["result"] is not None
            finished = client.get("/api/navigator", headers={"X-Session-Code": done})
            assert finished.status_code == 404  # a finished episode is not played again
    finally:
        server.send_signal(signal.SIGKILL)
        server.wait()

    records = {r.agent: r for r in load_run_records([out])}
    assert sorted(records) == ["frontier with human oracle", "human:p10", "human:p11"]
    assert success(records["human:p10"]) and success(records["human:p11"])
    assert records["human:p11"].dialog[0].answer == asked["dialog"][0]["answer"]  # type: ignore[index]
    abandoned = records["frontier with human oracle"]
    assert abandoned.error is not None and abandoned.error.startswith("abandoned")
    assert not success(abandoned)
