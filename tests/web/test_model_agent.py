"""A person answers the openai-vlm agent (against a local chat server) on the oracle page,
and the agent's next prompt carries the person's answer."""

from __future__ import annotations

import time
from pathlib import Path

import httpx
import pytest

from tests.oracle.llm.chat_server import chat_server, completion
from vlln.eval.results import load_run_records
from vlln.web.config import WebConfig

from .conftest import Study, start_server

ANSWER = "It is the <b>silver</b> one, right behind you."


@pytest.mark.slow
def test_the_agents_next_prompt_contains_the_persons_answer(study: Study, tmp_path: Path) -> None:
    script = ["<talk>What color is it?", "<move>←", "<move>STOP"]
    with chat_server([completion(text) for text in script]) as chat:
        options = {"base_url": chat.base_url, "model": "scripted-vlm", "backoff_s": "0.01"}
        config = WebConfig(
            episodes=tuple(study.episodes),
            out=tmp_path / "study",
            agent_options={"openai-vlm": options},
        )
        url, server, thread = start_server(config)
        try:
            with httpx.Client(base_url=url, timeout=30.0) as client:
                body = {"navigator": "openai-vlm", "oracle": "human", "episode_index": 0}
                code = client.post("/api/sessions", json=body).json()["oracle_code"]
                headers = {"X-Session-Code": code}
                view = client.get("/api/oracle", headers=headers).json()
                deadline = time.monotonic() + 120.0
                while view["question"] is None and view["result"] is None:
                    assert time.monotonic() < deadline, f"no question came: {view}"
                    view = client.get(
                        f"/api/oracle?after={view['version']}", headers=headers
                    ).json()
                assert view["question"] is not None, f"the episode ended unasked: {view}"
                assert view["question"]["text"] == "What color is it?"
                answer = {"number": view["question"]["number"], "answer": ANSWER}
                assert (
                    client.post("/api/oracle/answer", json=answer, headers=headers).status_code
                    == 200
                )
                while view["result"] is None:
                    assert time.monotonic() < deadline, f"the episode did not end: {view}"
                    view = client.get(
                        f"/api/oracle?after={view['version']}", headers=headers
                    ).json()
        finally:
            server.should_exit = True  # type: ignore[attr-defined]
            thread.join(timeout=30.0)
        requests = list(chat.requests)
    (record,) = load_run_records([config.out])
    assert record.agent == "openai-vlm with human oracle" and record.actions == [
        "TALK",
        "TURN_LEFT",
        "STOP",
    ]
    assert record.dialog[0].answer == ANSWER and record.dialog[0].backend == "human"
    answered = requests[1]["json"]["messages"][2]
    assert answered["role"] == "user" and answered["content"] == [{"type": "text", "text": ANSWER}]
