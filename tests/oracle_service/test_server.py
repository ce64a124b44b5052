"""The real server: uvicorn on loopback in a thread, spoken to over HTTP with httpx."""

from __future__ import annotations

import gc
import threading
import time

import httpx
import pytest

from vlln.cli import main
from vlln.errors import ConfigError
from vlln.oracle_service.config import ServiceConfig
from vlln.oracle_service.server import build_server, freeze_startup_objects
from vlln.tasks.spec import REFUSAL_MESSAGE

from .conftest import TOKEN, World

START_TIMEOUT = 15.0


def test_uvicorn_serves_a_session_over_loopback(world: World) -> None:
    server = build_server(ServiceConfig(token=TOKEN), "127.0.0.1", 0, log_level="warning")
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    try:
        deadline = time.monotonic() + START_TIMEOUT
        while not server.started:
            assert thread.is_alive() and time.monotonic() < deadline, "server did not start"
            time.sleep(0.02)
        host, port = server.servers[0].sockets[0].getsockname()[:2]
        assert host == "127.0.0.1"
        headers = {"Authorization": f"Bearer {TOKEN}"}
        with httpx.Client(base_url=f"http://127.0.0.1:{port}", timeout=10.0) as client:
            assert client.get("/v1/health").json()["status"] == "ok"
            assert client.post("/v1/sessions", json={}).status_code == 401
            created = client.post(
                "/v1/sessions",
                json={
                    "scene_id": world.scene_id,
                    "target_instance_id": world.target_id,
                    "dialog_budget": 1,
                },
                headers=headers,
            )
            assert created.status_code == 201
            ask_url = f"/v1/sessions/{created.json()['session_id']}/ask"
            json_headers = {**headers, "Content-Type": "application/json"}
            bad = client.post(ask_url, content=b'{"question": ', headers=json_headers)
            assert bad.status_code == 400 and bad.json()["error"] == "malformed JSON"
            question = {"question": "What color is it?", "pose": world.poses[0]}
            answer = client.post(ask_url, json=question, headers=headers).json()
            assert answer["answered"] and world.target_color in answer["answer"]
            refused = client.post(ask_url, json=question, headers=headers).json()
            assert refused["answer"] == REFUSAL_MESSAGE and not refused["answered"]
    finally:
        server.should_exit = True
        thread.join(timeout=START_TIMEOUT)
    assert not thread.is_alive()


def test_loopback_is_the_default_and_other_hosts_need_consent(
    capsys: pytest.CaptureFixture[str],
) -> None:
    with pytest.raises(ConfigError, match="allow_remote"):
        build_server(ServiceConfig(), "0.0.0.0", 0)
    with pytest.raises(ConfigError, match="token"):  # reproduction 5: refused, not warned
        build_server(ServiceConfig(), "0.0.0.0", 0, allow_remote=True)
    build_server(ServiceConfig(token=TOKEN), "0.0.0.0", 0, allow_remote=True)
    assert "with a bearer token" in capsys.readouterr().err
    with pytest.raises(ConfigError, match="port"):
        build_server(ServiceConfig(), "127.0.0.1", 70000)


@pytest.mark.parametrize("value", [None, ""])
def test_a_named_token_variable_that_is_unset_or_empty_is_refused(
    value: str | None, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """Reproduction 5: --token-env WRONG_NAME must not start without authentication."""
    monkeypatch.delenv("VLLN_TOKEN_TYPO", raising=False)
    if value is not None:
        monkeypatch.setenv("VLLN_TOKEN_TYPO", value)
    assert main(["oracle", "serve", "--token-env", "VLLN_TOKEN_TYPO", "--port", "1"]) == 2
    error = capsys.readouterr().err
    assert error.startswith("error: ") and "VLLN_TOKEN_TYPO" in error and error.count("\n") == 1


def test_objects_alive_at_start_are_left_out_of_full_collections() -> None:
    alive = len(gc.get_objects())
    try:
        assert freeze_startup_objects() >= alive // 2
        assert len(gc.get_objects()) < alive // 2  # a full pass no longer scans them
    finally:
        gc.unfreeze()
