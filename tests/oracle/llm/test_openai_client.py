"""The OpenAI-compatible client against a scripted server on 127.0.0.1."""

from __future__ import annotations

import json
import logging
import math
import re
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from tests.oracle.llm.chat_server import Scripted, chat_server, completion
from vlln.errors import ConfigError
from vlln.oracle.llm.accounting import Pricing
from vlln.oracle.llm.openai_client import MAX_REPLY_BYTES, OpenAIChatClient, OpenAISettings
from vlln.oracle.llm.protocol import (
    LanguageModelReplyError,
    LanguageModelRequestError,
    LanguageModelUnavailableError,
    Message,
)

KEY_ENV = "VLLN_TEST_LLM_KEY"
SECRET = "sk-test-5ecret-value"
MESSAGES = [Message("user", "Which way is the sofa?")]


def client_for(base_url: str, seed: int = 0, **settings: object) -> OpenAIChatClient:
    values: dict[str, Any] = {
        "model": "test-model",
        "base_url": base_url,
        "api_key_env": KEY_ENV,
        "timeout_s": 2.0,
        "max_retries": 2,
        "backoff_base_s": 0.001,
        "backoff_max_s": 1.0,
    }
    values.update(settings)
    return OpenAIChatClient(OpenAISettings(**values), rng=np.random.default_rng(seed))


def ask(client: OpenAIChatClient, text: str = "Which way is the sofa?", t: float = 0.0) -> str:
    return client.complete([Message("user", text)], max_tokens=16, temperature=t).text


def test_success_sends_the_chat_format_and_reads_text_and_usage() -> None:
    with chat_server([completion("Turn left.", 11, 4)]) as server, client_for(server.base_url) as c:
        result = c.complete(MESSAGES, max_tokens=32, temperature=0.5)
    assert result.text == "Turn left."
    assert (result.usage.prompt_tokens, result.usage.completion_tokens) == (11, 4)
    assert not result.cached and result.latency_ms > 0.0
    assert result.backend == "openai:test-model@127.0.0.1"
    (request,) = server.requests
    assert request["path"] == "/v1/chat/completions"
    assert request["json"] == {
        "model": "test-model",
        "messages": [{"role": "user", "content": "Which way is the sofa?"}],
        "max_tokens": 32,
        "temperature": 0.5,
    }


def test_a_timeout_is_retried() -> None:
    script = [Scripted(200, completion("late").body, delay_s=1.0), completion("on time")]
    with chat_server(script) as server, client_for(server.base_url, timeout_s=0.2) as client:
        assert ask(client) == "on time"
        assert len(server.requests) == 2
        assert client.ledger.requests == 1 and client.ledger.failed_requests == 0


def test_429_waits_for_retry_after_then_succeeds() -> None:
    script = [Scripted(429, {"error": "slow down"}, {"Retry-After": "0.3"}), completion("ok")]
    with chat_server(script) as server, client_for(server.base_url) as client:
        start = time.perf_counter()
        assert ask(client) == "ok"
        waited = time.perf_counter() - start
    assert len(server.requests) == 2
    assert waited >= 0.3  # the back-off alone would be about a millisecond


def test_500_is_retried_and_persistent_500_raises_after_all_attempts() -> None:
    with chat_server([Scripted(500, "boom"), completion("fine")]) as server:
        with client_for(server.base_url) as client:
            assert ask(client) == "fine"
        assert len(server.requests) == 2
    with (
        chat_server([Scripted(503, "down")]) as server,
        client_for(server.base_url, max_retries=3) as client,
        pytest.raises(LanguageModelUnavailableError, match="503") as caught,
    ):
        ask(client)
        assert len(server.requests) == 4  # the first attempt and three retries
        assert client.ledger.failed_requests == 1 and client.ledger.requests == 0
        assert caught.value.latency_ms > 0.0


def test_an_unreachable_server_is_unavailable() -> None:
    with chat_server([completion("x")]) as server:
        base_url = server.base_url
    with (
        client_for(base_url, max_retries=1) as client,  # the port is closed now
        pytest.raises(LanguageModelUnavailableError, match="2 attempts"),
    ):
        ask(client)


@pytest.mark.parametrize(
    ("body", "problem"),
    [
        ("this is not json", "not JSON"),
        ({"object": "chat.completion"}, "choices"),
        ({"choices": []}, "choices"),
        ({"choices": [{"message": {"role": "assistant", "content": None}}]}, "content"),
        ({"choices": [{"message": {"content": "hi"}}], "usage": {"prompt_tokens": -1}}, "usage"),
        ([1, 2], "not an object"),
        ('{"choices": ' + "[" * 100_000 + "]" * 100_000 + "}", "nested deeper"),
        ('{"choices": [], "usage": {"prompt_tokens": ' + "9" * 5000 + "}}", "5000 digits"),
        ('{"choices": [{"message": {"content": "\\ud800"}}]}', "surrogate"),
    ],
)
def test_malformed_replies_raise_a_typed_error_without_retrying(
    body: dict[str, object] | str | list[int], problem: str
) -> None:
    text = body if isinstance(body, str | dict) else str(body)
    with chat_server([Scripted(200, text)]) as server, client_for(server.base_url) as client:
        with pytest.raises(LanguageModelReplyError, match=problem):
            ask(client)
        assert len(server.requests) == 1


def test_401_is_not_retried_and_names_the_key_variable(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(KEY_ENV, SECRET)
    body = {"error": {"message": f"Incorrect API key provided: {SECRET}"}}
    with (
        chat_server([Scripted(401, body)]) as server,
        client_for(server.base_url) as client,
        pytest.raises(LanguageModelRequestError) as caught,
    ):
        ask(client)
    assert len(server.requests) == 1
    assert caught.value.status == 401
    assert KEY_ENV in str(caught.value) and SECRET not in str(caught.value)


def test_the_key_is_sent_as_a_bearer_header_and_never_logged(
    monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    monkeypatch.setenv(KEY_ENV, SECRET)
    caplog.set_level(logging.DEBUG)
    script = [Scripted(500, f"echo {SECRET}"), completion("ok")]
    with chat_server(script) as server, client_for(server.base_url) as client:
        assert ask(client) == "ok"
        text = repr(client)
    assert all(r["headers"]["authorization"] == f"Bearer {SECRET}" for r in server.requests)
    assert "retry 1 of 2" in caplog.text  # the retry was logged, with the body masked
    assert SECRET not in caplog.text and SECRET not in text
    monkeypatch.delenv(KEY_ENV)
    with chat_server([completion("ok")]) as server, client_for(server.base_url) as client:
        ask(client)
    assert "authorization" not in server.requests[0]["headers"]


def test_the_cache_answers_repeats_without_a_request(tmp_path: Path) -> None:
    with chat_server([completion("first"), completion("second")]) as server:
        with client_for(server.base_url, cache_dir=tmp_path) as client:
            fresh = client.complete(MESSAGES, max_tokens=16, temperature=0.0)
            again = client.complete(MESSAGES, max_tokens=16, temperature=0.0)
        assert len(server.requests) == 1
        assert again.text == fresh.text == "first"
        assert again.cached and again.usage.total_tokens == 0 and again.latency_ms == 0.0
        assert client.ledger.cached_requests == 1 and client.ledger.requests == 1
        with client_for(server.base_url, cache_dir=tmp_path) as other:  # survives the process
            assert ask(other) == "first"
            assert ask(other, t=0.7) == "second"  # other parameters, another entry
        assert len(server.requests) == 2
    assert list(tmp_path.rglob("*.tmp")) == []


def test_tokens_and_cost_add_up() -> None:
    pricing = Pricing(prompt_per_1k=2.5, completion_per_1k=10.0)
    script = [completion("a", 100, 20), completion("b", 300, 40), Scripted(400, "bad")]
    with chat_server(script) as server, client_for(server.base_url, pricing=pricing) as client:
        ask(client, "one")
        ask(client, "two")
        with pytest.raises(LanguageModelRequestError):
            ask(client, "three")
    ledger = client.ledger
    assert (ledger.requests, ledger.failed_requests) == (2, 1)
    assert (ledger.prompt_tokens, ledger.completion_tokens) == (400, 60)
    assert ledger.total_tokens == 460
    assert math.isclose(ledger.cost, (400 * 2.5 + 60 * 10.0) / 1000.0)


def test_back_off_jitter_comes_from_the_seeded_generator(
    caplog: pytest.LogCaptureFixture,
) -> None:
    def delays(seed: int) -> list[str]:
        caplog.clear()
        script = [Scripted(500, "x"), Scripted(502, "y"), completion("ok")]
        with (
            chat_server(script) as server,
            client_for(server.base_url, seed, backoff_base_s=0.02) as client,
        ):
            caplog.set_level(logging.INFO)
            ask(client)
        return re.findall(r"in (\d+\.\d+) s", caplog.text)

    first, again, other = delays(3), delays(3), delays(4)
    assert len(first) == 2 and first == again and first != other
    low, high = float(first[0]), float(first[1])
    assert 0.01 <= low <= 0.02 and 0.02 <= high <= 0.04  # half to all of 0.02 * 2**k


def test_https_is_required_except_for_loopback_hosts() -> None:
    for url in (
        "https://api.openai.com/v1",
        "http://127.0.0.1:8000/v1",
        "http://localhost:11434/v1",
    ):
        OpenAISettings(model="m", base_url=url)
    OpenAISettings(model="m", base_url="http://[::1]:8000/v1")
    for url in ("http://api.openai.com/v1", "http://10.0.0.5:8000/v1", "ftp://x/v1", "api/v1"):
        with pytest.raises(ConfigError, match="https"):
            OpenAISettings(model="m", base_url=url)


def test_invalid_settings_and_arguments_raise_config_errors() -> None:
    bad: list[dict[str, Any]] = [
        {"model": " "},
        {"model": "m", "api_key_env": "NOT A NAME"},
        {"model": "m", "timeout_s": 0.0},
        {"model": "m", "max_retries": -1},
        {"model": "m", "backoff_base_s": 2.0, "backoff_max_s": 1.0},
    ]
    for values in bad:
        with pytest.raises(ConfigError):
            OpenAISettings(**values)
    with pytest.raises(ConfigError, match="prompt_per_1k"):
        Pricing(prompt_per_1k=-1.0)
    client = client_for("http://127.0.0.1:9/v1")
    with pytest.raises(ConfigError, match="max_tokens"):
        client.complete(MESSAGES, max_tokens=0, temperature=0.0)
    with pytest.raises(ConfigError, match="temperature"):
        client.complete(MESSAGES, max_tokens=5, temperature=3.0)
    client.close()


def test_a_trickling_server_is_cut_off_at_the_requests_deadline() -> None:
    # One byte every 50 ms never trips a per-read timeout; the whole reply would take over 10 s.
    reply = Scripted(200, completion("Turn left.").body, trickle_s=0.05)
    with (
        chat_server([reply]) as server,
        client_for(server.base_url, timeout_s=0.5, max_retries=0) as client,
    ):
        with pytest.raises(LanguageModelUnavailableError, match=r"0\.5 s deadline") as caught:
            ask(client)
        assert client.ledger.failed_requests == 1 and client.ledger.requests == 0
    assert len(json.dumps(reply.body)) * 0.05 > 10.0
    assert caught.value.latency_ms < 5000.0  # cut off long before the reply could end


def test_a_reply_longer_than_the_cap_is_refused_unread() -> None:
    huge = completion("x" * (MAX_REPLY_BYTES + 1))
    with (
        chat_server([huge]) as server,
        client_for(server.base_url) as client,
        pytest.raises(LanguageModelReplyError, match="ignore max_tokens"),
    ):
        ask(client)
    with (
        chat_server([huge, completion("Turn left.")]) as server,
        client_for(server.base_url, retry_bad_replies=True) as client,
    ):
        assert ask(client) == "Turn left."
