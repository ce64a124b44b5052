"""The language-model oracle: at most two calls, grounded answers, fallbacks that are recorded."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from tests.oracle.episodes import iign_episode
from tests.oracle.llm.chat_server import Scripted, chat_server, completion
from vlln.errors import ConfigError
from vlln.oracle.helpful.oracle import HelpfulOracle
from vlln.oracle.llm.offline import OfflineLanguageModel
from vlln.oracle.llm.openai_client import OpenAIChatClient, OpenAISettings
from vlln.oracle.llm.prompts import QUESTION_MARKER, REFERENCE_MARKER, field_value
from vlln.oracle.llm_oracle import LLMOracle
from vlln.oracle.rule_oracle import TYPE_REFUSAL, RuleOracle
from vlln.oracle.settings import OracleBackend, OracleSettings
from vlln.sim.agent import AgentState
from vlln.sim.simulator import Simulator
from vlln.sim.viewpoints import view_points
from vlln.tasks.env import NavigationEnv
from vlln.tasks.oracle_protocol import EpisodeContext, Oracle, Question, QuestionType
from vlln.tasks.record import DialogTurn, EpisodeRecord
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import Talk, TaskConfig
from vlln.world.model import ObjectInstance

QUESTIONS = (
    "What color is it?",
    "Which room is it in?",
    "Which way should I go?",
    "How do I get there?",
    "What should I do next?",
    "Is this the one?",
    "How far is it?",
    "What time is it?",
)


@pytest.fixture(scope="module")
def target(sim: Simulator) -> ObjectInstance:
    component = sim.grid.largest_component()
    for inst in sim.house.instances:
        goals = view_points(sim.grid, inst.box)
        if inst.attributes.color and any(sim.grid.component_of(*g) == component for g in goals):
            return inst
    raise AssertionError("the house has no reachable coloured object")


def context(sim: Simulator, target: ObjectInstance) -> EpisodeContext:
    return EpisodeContext(sim, target, tuple(view_points(sim.grid, target.box)))


def question(sim: Simulator, text: str, seed: int = 0) -> Question:
    x, z = sim.grid.sample_navigable_point(
        np.random.default_rng(seed), sim.grid.largest_component()
    )
    state = AgentState((x, 0.0, z), 0.0)
    return Question(text, state, sim.render(state))


def server_oracle(base_url: str, max_retries: int = 1) -> LLMOracle:
    settings = OpenAISettings(
        model="test-model",
        base_url=base_url,
        timeout_s=2.0,
        max_retries=max_retries,
        backoff_base_s=0.001,
    )
    return LLMOracle(OpenAIChatClient(settings, rng=np.random.default_rng(0)), seed=3)


def prompt_of(request: dict[str, object]) -> str:
    body = request["json"]
    assert isinstance(body, dict)
    return str(body["messages"][0]["content"])


def test_offline_model_gives_the_rule_oracles_answers_word_for_word(
    sim: Simulator, target: ObjectInstance
) -> None:
    llm: Oracle = LLMOracle(OfflineLanguageModel(), seed=5)
    rules = RuleOracle(seed=5)
    for oracle in (llm, rules):
        oracle.start(context(sim, target))
    for seed in range(2):
        for text in QUESTIONS:
            asked = question(sim, text, seed)
            mine, theirs = llm.answer(asked), rules.answer(asked)
            assert (mine.answer, mine.question_type) == (theirs.answer, theirs.question_type)
            assert mine.backend == "offline" and theirs.backend == "rules"
            assert not mine.fallback and mine.prompt_tokens == mine.completion_tokens == 0


def test_the_model_classifies_then_rewords_grounded_facts(
    sim: Simulator, target: ObjectInstance
) -> None:
    asked = question(sim, "Which way should I go?")
    reference = RuleOracle(seed=3)
    reference.start(context(sim, target))
    expected = reference.answer(asked).answer
    script = [completion(" Route\n", 50, 1), completion("Head left, past the sofa.", 120, 9)]
    with chat_server(script) as server:
        oracle = server_oracle(server.base_url)
        oracle.start(context(sim, target))
        reply = oracle.answer(asked)
    assert (reply.answer, reply.question_type) == ("Head left, past the sofa.", QuestionType.ROUTE)
    assert (reply.prompt_tokens, reply.completion_tokens) == (170, 10)
    assert reply.backend == "openai:test-model@127.0.0.1" and reply.latency_ms > 0.0
    assert not reply.fallback
    classify, word = (prompt_of(r) for r in server.requests)
    assert field_value(classify, QUESTION_MARKER) == "Which way should I go?"
    assert "Heading to Target: " in word and "Next Step: " in word
    assert field_value(word, REFERENCE_MARKER) == " ".join(expected.split())


def test_attribute_prompts_hold_the_targets_metadata(
    sim: Simulator, target: ObjectInstance
) -> None:
    with chat_server([completion("attribute"), completion("It is red.")]) as server:
        oracle = server_oracle(server.base_url)
        oracle.start(context(sim, target))
        oracle.answer(question(sim, "Tell me about its color."))
    info = field_value(prompt_of(server.requests[1]), "Goal Information: ")
    assert info is not None
    assert f"category: {target.category}" in info and f"color: {target.attributes.color}" in info


def test_disambiguation_needs_one_call_and_stays_deterministic(
    sim: Simulator, target: ObjectInstance
) -> None:
    asked = question(sim, "Is this the one?")
    rules = RuleOracle(seed=3)
    rules.start(context(sim, target))
    with chat_server([completion("disambiguation", 40, 2)]) as server:
        oracle = server_oracle(server.base_url)
        oracle.start(context(sim, target))
        reply = oracle.answer(asked)
    assert len(server.requests) == 1
    assert reply.answer == rules.answer(asked).answer
    assert reply.question_type == QuestionType.DISAMBIGUATION and reply.prompt_tokens == 40


def test_a_different_type_from_the_model_is_answered_without_a_reference(
    sim: Simulator, target: ObjectInstance
) -> None:
    with chat_server([completion("other"), completion("It is noon.")]) as server:
        oracle = server_oracle(server.base_url)
        oracle.start(context(sim, target))
        reply = oracle.answer(question(sim, "What color is it?"))
    assert reply.question_type == QuestionType.OTHER and reply.answer == "It is noon."
    word = prompt_of(server.requests[1])
    assert field_value(word, REFERENCE_MARKER) is None and "Target Detected: " in word


def test_unparseable_classification_uses_the_offline_type(
    sim: Simulator, target: ObjectInstance
) -> None:
    with chat_server([completion("Hmm, hard to say."), completion("Red.")]) as server:
        oracle = server_oracle(server.base_url)
        oracle.start(context(sim, target))
        reply = oracle.answer(question(sim, "What color is it?"))
    assert reply.question_type == QuestionType.ATTRIBUTE and reply.answer == "Red."
    assert reply.fallback and len(server.requests) == 2


@pytest.mark.parametrize(
    "script",
    [
        [Scripted(500, "down")],  # the server is down: classification fails, no second call
        [completion("attribute", 30, 1), Scripted(200, "not json")],
        [completion("attribute", 30, 1), Scripted(200, {"choices": []})],
        [completion("attribute", 30, 1), completion("   ", 0, 0)],  # an empty answer
        [completion("attribute", 30, 1), Scripted(200, "[" * 100_000 + "]" * 100_000)],
    ],
)
def test_failed_calls_fall_back_to_the_rule_answer_and_say_so(
    sim: Simulator, target: ObjectInstance, script: list[Scripted]
) -> None:
    asked = question(sim, "What color is it?")
    rules = RuleOracle(seed=3)
    rules.start(context(sim, target))
    offline = rules.answer(asked)
    with chat_server(script) as server:
        oracle = server_oracle(server.base_url, max_retries=2)
        oracle.start(context(sim, target))
        reply = oracle.answer(asked)
    assert (reply.answer, reply.question_type) == (offline.answer, offline.question_type)
    assert reply.fallback and reply.backend.startswith("openai:")
    if script[0].status == 500:
        assert len(server.requests) == 3 and reply.prompt_tokens == 0
    else:
        assert len(server.requests) == 2 and reply.prompt_tokens == 30


def test_misuse_raises_config_errors(sim: Simulator) -> None:
    with pytest.raises(ConfigError, match="seed"):
        LLMOracle(OfflineLanguageModel(), seed=1, fallback=RuleOracle(seed=2))
    with pytest.raises(ConfigError, match="max_tokens"):
        LLMOracle(OfflineLanguageModel(), max_tokens=0)
    with pytest.raises(ConfigError, match="start"):
        LLMOracle(OfflineLanguageModel()).answer(question(sim, "What color is it?"))


def test_the_environment_records_backend_latency_and_tokens(
    scenes: SceneCache, sim: Simulator, target: ObjectInstance
) -> None:
    episode = iign_episode(sim, target, "llm-oracle-test")
    script = [completion("attribute", 60, 1), completion("It is red.", 90, 5)]
    with chat_server(script) as server:
        env = NavigationEnv(
            [episode], TaskConfig(dialog_budget=1), scenes, server_oracle(server.base_url)
        )
        env.reset(options={"episode_index": 0})
        observation, *_ = env.step(Talk("What colour is it?"))
        env.step(Talk("And its material?"))
    assert observation["oracle_answer"] == "It is red."
    record = env.record("test")
    answered, refused = record.dialog
    assert answered.backend == "openai:test-model@127.0.0.1" and not answered.fallback
    assert (answered.prompt_tokens, answered.completion_tokens) == (150, 6)
    assert answered.latency_ms > 0.0
    assert refused.backend == "none" and refused.prompt_tokens == 0
    loaded = EpisodeRecord.from_json(record.to_json())
    assert loaded.dialog == record.dialog
    old = record.to_json()
    old["dialog"] = [
        {k: turn[k] for k in ("step", "question", "answer", "question_type", "answered")}
        for turn in old["dialog"]
    ]
    assert EpisodeRecord.from_json(old).dialog[0] == DialogTurn(
        answered.step, answered.question, answered.answer, "attribute", True
    )


def test_a_trickling_server_is_cut_off_and_the_rule_answer_given(
    sim: Simulator, target: ObjectInstance
) -> None:
    asked = question(sim, "What color is it?")
    rules = RuleOracle(seed=3)
    rules.start(context(sim, target))
    offline = rules.answer(asked)
    # One byte every 50 ms: no read waits long, but the reply would take over 10 s.
    trickle = Scripted(200, completion("attribute").body, trickle_s=0.05)
    with chat_server([trickle]) as server:
        settings = OpenAISettings(
            model="test-model", base_url=server.base_url, timeout_s=0.5, max_retries=0
        )
        client = OpenAIChatClient(settings, rng=np.random.default_rng(0))
        oracle = LLMOracle(client, seed=3)
        oracle.start(context(sim, target))
        reply = oracle.answer(asked)
    assert reply.fallback and reply.answer == offline.answer
    assert client.ledger.failed_requests >= 1
    assert reply.latency_ms < 5000.0  # cut off long before the reply could end


BEYOND_THE_SCHEMA = ("Are you sure?", "Did I pass it?", "Is it near a window?")


def test_with_help_the_offline_model_gives_the_helpful_oracles_answers(
    sim: Simulator, target: ObjectInstance
) -> None:
    llm = LLMOracle(OfflineLanguageModel(), seed=5, helpful=True)
    helpful = HelpfulOracle(RuleOracle(seed=5))
    for oracle in (llm, helpful):
        oracle.start(context(sim, target))
    kinds = set()
    for text in (*QUESTIONS, *BEYOND_THE_SCHEMA):
        asked = question(sim, text)
        mine, theirs = llm.answer(asked), helpful.answer(asked)
        assert (mine.answer, mine.question_type) == (theirs.answer, theirs.question_type)
        assert mine.help_kind == theirs.help_kind and mine.backend == "offline"
        kinds.add(mine.help_kind)
    assert {"schema", "confirmation", "passed", "window"} <= kinds
    plain = LLMOracle(OfflineLanguageModel(), seed=5)
    plain.start(context(sim, target))
    assert plain.answer(question(sim, "Are you sure?")).help_kind == ""


def test_help_beyond_the_schema_is_one_call_rewording_the_grounded_answer(
    sim: Simulator, target: ObjectInstance
) -> None:
    asked = question(sim, "Is it near a window?")
    reference = HelpfulOracle(RuleOracle(seed=3))
    reference.start(context(sim, target))
    expected = reference.answer(asked)
    settings = OpenAISettings(model="m", timeout_s=2.0, max_retries=0)
    with chat_server([completion("Yes, by the window.", 80, 5)]) as server:
        settings = dataclasses.replace(settings, base_url=server.base_url)
        oracle = OracleSettings(OracleBackend.HELPFUL, settings).make(3)
        oracle.start(context(sim, target))
        reply = oracle.answer(asked)
    assert isinstance(oracle, LLMOracle) and len(server.requests) == 1
    assert (reply.answer, reply.help_kind) == ("Yes, by the window.", "window")
    assert reply.question_type == expected.question_type and reply.prompt_tokens == 80
    word = prompt_of(server.requests[0])
    assert field_value(word, REFERENCE_MARKER) == " ".join(expected.answer.split())
    assert field_value(word, "Help Asked: ") == "window" and "Target Detected: " in word


def test_a_question_about_nothing_in_the_house_is_refused_without_a_call(
    sim: Simulator, target: ObjectInstance
) -> None:
    settings = OpenAISettings(model="m", timeout_s=2.0, max_retries=0)
    with chat_server([completion("Mix flour and water.", 80, 5)]) as server:
        settings = dataclasses.replace(settings, base_url=server.base_url)
        oracle = OracleSettings(OracleBackend.HELPFUL, settings).make(3)
        oracle.start(context(sim, target))
        reply = oracle.answer(question(sim, "How do I bake bread?"))
    assert not server.requests
    assert (reply.answer, reply.help_kind) == (TYPE_REFUSAL, "off_topic")
