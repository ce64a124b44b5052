"""The API's guards: codes open only their role, the token, body sizes, rates, headers."""

from __future__ import annotations

import secrets
from pathlib import Path

import httpx
import pytest
from fastapi.testclient import TestClient

from tests.oracle.llm.chat_server import chat_server, completion
from vlln.cli import main
from vlln.errors import ConfigError
from vlln.eval.results import load_run_records
from vlln.oracle.llm.openai_client import OpenAISettings
from vlln.web.app import create_app
from vlln.web.config import WebConfig
from vlln.web.server import build_server

from .conftest import Served, Study

TOKEN = "a-token-of-sixteen-plus"


def test_a_code_opens_only_its_own_role(served: Served) -> None:
    with httpx.Client(base_url=served.url, timeout=30.0) as client:
        body = {"navigator": "human", "participant": "p20", "oracle": "human", "episode_index": 3}
        created = client.post("/api/sessions", json=body).json()
        navigator, oracle = created["navigator_code"], created["oracle_code"]
        assert len(navigator) >= 16 and navigator != oracle
        assert client.post("/api/join", json={"code": oracle}).json()["page"] == "/answer"
        assert (
            client.get("/api/oracle/map", headers={"X-Session-Code": navigator}).status_code == 404
        )
        assert client.get("/api/oracle", headers={"X-Session-Code": navigator}).status_code == 404
        assert client.get("/api/navigator", headers={"X-Session-Code": oracle}).status_code == 404
        assert client.get("/api/navigator", headers={"X-Session-Code": "guess"}).status_code == 404
        again = client.post("/api/sessions", json=body)
        assert again.status_code == 409 and "has played or is playing" in again.json()["detail"]
        bad = client.post("/api/sessions", json={**body, "participant": "<b>x</b>"})
        assert bad.status_code == 409 and "not a valid label" in bad.json()["detail"]
        page = client.get("/navigate")
        assert "script-src 'self'" in page.headers["content-security-policy"]
        assert page.headers["referrer-policy"] == "no-referrer"


def test_errors_are_the_shared_json_error_bodies(study: Study, tmp_path: Path) -> None:
    config = WebConfig(episodes=tuple(study.episodes), out=tmp_path / "errors")
    with TestClient(create_app(config)) as client:
        invalid = client.post("/api/join", json={"code": ""})
        assert invalid.status_code == 422 and invalid.json()["error"] == "invalid request"
        assert [problem["field"] for problem in invalid.json()["detail"]] == ["body.code"]
        malformed = client.post(
            "/api/join", content=b'{"code": ', headers={"Content-Type": "application/json"}
        )
        assert malformed.status_code == 400 and malformed.json()["error"] == "malformed JSON"
        missing = client.get("/api/nothing-here")
        assert missing.status_code == 404 and missing.json()["error"] == "not found"
        form = client.post("/api/join", content=b"code=x", headers={"Content-Type": "text/plain"})
        assert form.status_code == 415


def test_the_token_guards_the_lobby_and_other_hosts_need_one(study: Study, tmp_path: Path) -> None:
    config = WebConfig(episodes=tuple(study.episodes), out=tmp_path / "a", token=TOKEN)
    with TestClient(create_app(config)) as client:
        assert client.get("/api/lobby").status_code == 401
        wrong = {"Authorization": "Bearer not-the-token-at-all"}
        assert (
            client.post("/api/sessions", json={"navigator": "human"}, headers=wrong).status_code
            == 401
        )
        assert (
            client.get("/api/lobby", headers={"Authorization": f"Bearer {TOKEN}"}).status_code
            == 200
        )
    open_config = WebConfig(episodes=tuple(study.episodes), out=tmp_path / "b")
    with pytest.raises(ConfigError, match="needs an access token"):
        build_server(open_config, "0.0.0.0", 0)
    build_server(config, "0.0.0.0", 0)  # with a token: built, never started
    with pytest.raises(ConfigError, match="at least 16 characters"):
        WebConfig.build({"episodes": tuple(study.episodes), "out": tmp_path / "c", "token": "x"})


def test_bodies_and_request_rates_are_bounded(study: Study, tmp_path: Path) -> None:
    config = WebConfig(
        episodes=tuple(study.episodes),
        out=tmp_path / "a",
        max_body_bytes=512,
        requests_per_second=1.0,
        request_burst=5,
    )
    with TestClient(create_app(config)) as client:
        huge = {"navigator": "human", "participant": "x" * 1000}
        assert client.post("/api/sessions", json=huge).status_code == 413
        codes = [client.get("/api/health").status_code for _ in range(8)]
        assert codes[:4] == [200] * 4 and codes[-1] == 429


def test_made_up_session_codes_share_the_address_bucket(study: Study, tmp_path: Path) -> None:
    config = WebConfig(
        episodes=tuple(study.episodes),
        out=tmp_path / "a",
        requests_per_second=1.0,
        request_burst=5,
    )
    with TestClient(create_app(config)) as client:
        body = {"navigator": "human", "participant": "p40", "oracle": "rules"}
        code = client.post("/api/sessions", json=body).json()["navigator_code"]
        made_up = [secrets.token_urlsafe(12) for _ in range(8)]
        codes = [
            client.get("/api/health", headers={"X-Session-Code": c}).status_code for c in made_up
        ]
        assert codes[:4] == [200] * 4 and codes[-1] == 429
        # A code the server issued is a page of its own, with its own bucket.
        page = client.get("/api/navigator", headers={"X-Session-Code": code})
        assert page.status_code == 200


@pytest.mark.slow
def test_an_idle_episode_is_recorded_as_abandoned(study: Study, tmp_path: Path) -> None:
    config = WebConfig(episodes=tuple(study.episodes), out=tmp_path / "a", idle_limit_s=0.5)
    with TestClient(create_app(config)) as client:
        body = {"navigator": "human", "participant": "p30", "oracle": "rules"}
        code = client.post("/api/sessions", json=body).json()["navigator_code"]
        view = client.get("/api/navigator", headers={"X-Session-Code": code}).json()
        while view["result"] is None:
            after = view["version"]
            view = client.get(
                f"/api/navigator?after={after}", headers={"X-Session-Code": code}
            ).json()
        assert view["status"] == "abandoned" and view["result"]["success"] is False
    (record,) = load_run_records([config.out])
    assert record.agent == "human:p30" and record.error is not None
    assert record.error.startswith("abandoned: no action for")


@pytest.mark.slow
def test_a_navigator_who_leaves_frees_the_slot_at_once(study: Study, tmp_path: Path) -> None:
    config = WebConfig(episodes=tuple(study.episodes), out=tmp_path / "a", max_live_sessions=1)
    with TestClient(create_app(config)) as client:
        body = {"navigator": "human", "participant": "p31", "oracle": "rules"}
        code = client.post("/api/sessions", json=body).json()["navigator_code"]
        full = client.post("/api/sessions", json=body | {"participant": "p32"})
        assert full.status_code >= 400 and "the limit is 1" in full.text
        view = client.post("/api/navigator/end", headers={"X-Session-Code": code}).json()
        assert view["status"] == "abandoned" and view["result"]["success"] is False
        again = client.post("/api/navigator/end", headers={"X-Session-Code": code})
        assert again.json()["status"] == "abandoned"  # ending twice changes nothing
        assert client.post("/api/sessions", json=body | {"participant": "p32"}).status_code == 201
    (record, *_) = load_run_records([config.out])
    assert (
        record.agent == "human:p31" and record.error == "abandoned: the navigator ended the session"
    )


def test_a_person_asks_the_language_model_oracle(study: Study, tmp_path: Path) -> None:
    script = [completion("attribute"), completion("The bin is silver and stands by the door.")]
    with chat_server(script) as chat:
        llm = OpenAISettings(model="scripted-oracle", base_url=chat.base_url, max_retries=0)
        config = WebConfig(episodes=tuple(study.episodes), out=tmp_path / "a", llm=llm)
        with TestClient(create_app(config)) as client:
            oracles = client.get("/api/lobby").json()["oracles"]
            assert oracles == ["rules", "helpful", "llm", "human"]
            headers = _playing(client, "p40", "llm")
            asked = client.post(
                "/api/navigator/ask", json={"question": "What color is it?"}, headers=headers
            )
            assert (
                asked.json()["dialog"][0]["answer"] == "The bin is silver and stands by the door."
            )
            assert client.post(
                "/api/navigator/act", json={"action": "stop"}, headers=headers
            ).json()["result"]
    (record,) = load_run_records([config.out])
    assert record.agent == "human:p40 with llm oracle" and record.oracle == "llm"
    assert record.dialog[0].backend.startswith("openai:scripted-oracle")


def test_a_person_asks_the_helpful_oracle(study: Study, tmp_path: Path) -> None:
    config = WebConfig(episodes=tuple(study.episodes), out=tmp_path / "a")
    with TestClient(create_app(config)) as client:
        assert client.get("/api/lobby").json()["oracles"] == ["rules", "helpful", "human"]
        headers = _playing(client, "p41", "helpful")
        asked = client.post(
            "/api/navigator/ask", json={"question": "Should I go upstairs?"}, headers=headers
        )
        assert asked.json()["dialog"][0]["answer"].endswith(
            "This house has one floor, and it is on it."
        )
        client.post("/api/navigator/act", json={"action": "stop"}, headers=headers)
    (record,) = load_run_records([config.out])
    assert record.agent == "human:p41 with helpful oracle" and record.oracle == "helpful"
    assert (record.dialog[0].backend, record.dialog[0].help_kind) == ("helpful", "floor")


def test_the_command_line_names_bad_settings_in_one_line(
    study: Study, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "file").write_text("not a folder")
    source = ["--episode-file", str(study.episode_file)]
    assert main(["serve", "web", *source, "--out", str(tmp_path / "file")]) == 2
    assert "is a file, not a folder; give a folder" in capsys.readouterr().err
    assert main(["serve", "web", *source, "--out", str(tmp_path / "a"), "--host", "0.0.0.0"]) == 2
    assert "needs an access token: set VLLN_WEB_TOKEN" in capsys.readouterr().err
    (tmp_path / "b").mkdir()
    (tmp_path / "b" / "web.json").write_text('{"source": "split val, 3 houses"}')
    assert main(["serve", "web", *source, "--out", str(tmp_path / "b")]) == 2
    assert "holds a study with other settings" in capsys.readouterr().err


def _playing(client: TestClient, participant: str, oracle: str) -> dict[str, str]:
    """The headers of a person's navigator session with ``oracle``, once its episode plays."""
    body = {"navigator": "human", "participant": participant, "oracle": oracle}
    headers = {"X-Session-Code": client.post("/api/sessions", json=body).json()["navigator_code"]}
    view = client.get("/api/navigator", headers=headers).json()
    while view["status"] != "playing":
        view = client.get(f"/api/navigator?after={view['version']}", headers=headers).json()
    return headers
