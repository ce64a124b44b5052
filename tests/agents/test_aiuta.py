"""The AIUTA-style agent against a local scripted OpenAI-compatible server: its
self-dialogue, the questions its trigger asks the oracle, and server failures."""

from __future__ import annotations

import math
from typing import Any

import pytest

from tests.agents import world
from tests.oracle.llm.chat_server import ChatServer, Scripted, chat_server, completion
from vlln.agents.aiuta import AiutaAgent
from vlln.agents.registry import make_agent
from vlln.errors import ConfigError
from vlln.sim.simulator import Simulator
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.spec import TaskType
from vlln.tasks.taxonomy import classify

RED = [
    "A red chair standing on a wooden floor.",  # description (VLM)
    "1. What colour is the chair?\n2. Is there a table next to it?",  # self-questions (LLM)
    "Red.",  # first self-question (VLM)
    "I don't know.",  # second: unsure, dropped
    "A red chair.",  # refined description (LLM)
    "Score: 5\nQuestion: What color is the chair you are looking for?",  # trigger: ask
    "Score: 1\nQuestion: none",  # trigger after the answer "It is blue.": explore on
]
BLUE = [
    "A blue chair in a small room.",
    "What colour is the chair?",
    "Blue.",
    "A blue chair.",
    "Score: 9\nQuestion: none",  # stop at it
]


@pytest.fixture(scope="module")
def sim() -> Simulator:
    return Simulator(world.two_room_house())


def agent_for(server: ChatServer, **options: str) -> AiutaAgent:
    values = {"base_url": server.base_url, "model": "scripted-vlm", "backoff_s": "0.01"}
    agent = make_agent("aiuta", 3, options={**values, **options})
    assert isinstance(agent, AiutaAgent)
    return agent


def play(sim: Simulator, agent: AiutaAgent, budget: int) -> EpisodeRecord:
    # Start in room A facing the red chair; the blue one, the target, is behind the door.
    episode = world.episode(sim, world.BLUE_CHAIR, (3.5, 2.0), -math.pi / 2)
    env = world.make_env(sim, [episode], TaskType.IIGN, budget=budget)
    world.play(env, agent)
    return env.record("aiuta", model_calls=agent.model_calls(), stop_reason=agent.stop_reason())


def user_text(request: dict[str, Any]) -> str:
    content = request["json"]["messages"][0]["content"]
    if isinstance(content, str):
        return content
    return "".join(part.get("text", "") for part in content)


def test_the_self_dialogue_asks_the_oracle_and_stops_at_the_described_chair(
    sim: Simulator,
) -> None:
    with chat_server([completion(text) for text in RED + BLUE]) as server:
        record = play(sim, agent_for(server), budget=5)
        requests = list(server.requests)
    assert classify(record) == "success"
    (turn,) = record.dialog
    assert turn.question == "What color is the chair you are looking for?" and turn.answered
    assert "blue" in turn.answer.lower()
    assert [call.text for call in record.model_calls] == RED + BLUE
    texts = [user_text(r) for r in requests]
    # The VLM calls show the view; the LLM calls are text only.
    with_image = [isinstance(r["json"]["messages"][0]["content"], list) for r in requests]
    assert with_image[:7] == [True, False, True, True, False, False, False]
    # The unsure answer is dropped before the description is rewritten ...
    assert "Q: What colour is the chair?\nA: Red." in texts[4] and "table" not in texts[4]
    # ... and the oracle's answer reaches the trigger's facts.
    assert "The user said: " + turn.answer in texts[6]
    assert "Search for the chair." in texts[5]


def test_without_a_budget_it_never_asks_and_decides_alone(sim: Simulator) -> None:
    script = [*RED[:5], "Score: 5\nQuestion: Is it red?", *BLUE]
    with chat_server([completion(text) for text in script]) as server:
        record = play(sim, agent_for(server), budget=0)
    assert record.dialog == []  # a middling score without questions left: explore on
    assert classify(record) == "success"


def test_server_failures_are_failed_steps_and_counted(sim: Simulator) -> None:
    script = [Scripted(503, "down"), *map(completion, RED + BLUE)]
    with chat_server(script) as server:
        record = play(sim, agent_for(server, max_retries="0"), budget=5)
    assert record.failures == {"server": 1}
    assert record.failed_actions == 1 and "FAILED:server" in record.actions
    assert record.model_calls[0].text is None and "503" in (record.model_calls[0].error or "")
    # the object is examined again at the next step, and the dialogue goes on to success
    assert [call.text for call in record.model_calls[1:]] == RED + BLUE
    assert classify(record) == "success"


def test_a_trigger_reply_without_a_score_is_a_parse_failure(sim: Simulator) -> None:
    script = [*RED[:5], "I think it might be the one.", *RED[5:], *BLUE]
    with chat_server([completion(text) for text in script]) as server:
        record = play(sim, agent_for(server), budget=5)
    assert record.failures == {"parse": 1}
    assert classify(record) == "success"


def test_options_are_checked_and_the_detector_chosen() -> None:
    with chat_server([completion("x")]) as server:
        agent = make_agent(
            "aiuta", 0, detector="noisy", options={"base_url": server.base_url, "model": "m"}
        )
        assert isinstance(agent, AiutaAgent) and agent.detector == "noisy"
        with pytest.raises(ConfigError, match="stop_score"):
            make_agent(
                "aiuta", 0, options={"base_url": server.base_url, "model": "m", "stop_score": "11"}
            )
    with pytest.raises(ConfigError, match="--model"):
        make_agent("aiuta", 0, options={"base_url": "http://127.0.0.1:9/v1"})
