"""The oracle's ablation settings: question types refused with the paper's text at the cost of
their turn, and disambiguation answered with yes/no alone (plain) or with cues."""

from __future__ import annotations

import numpy as np

from tests.oracle.episodes import iign_episode
from tests.oracle.llm.chat_server import chat_server, completion
from tests.oracle.test_llm_oracle import context, question, target
from tests.oracle.test_rule_oracle import QUESTIONS, _states
from vlln.eval.config import EvalConfig
from vlln.oracle.disambiguation import PLAIN_NO
from vlln.oracle.llm.openai_client import OpenAIChatClient, OpenAISettings
from vlln.oracle.llm_oracle import LLMOracle
from vlln.oracle.rule_oracle import TYPE_REFUSAL, RuleOracle
from vlln.oracle.settings import Disambiguation, OracleSettings
from vlln.sim.simulator import Simulator
from vlln.tasks.env import NavigationEnv
from vlln.tasks.episode import Episode
from vlln.tasks.oracle_protocol import Question, QuestionType
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import REFUSAL_MESSAGE, Talk, TaskConfig
from vlln.world.model import ObjectInstance

__all__ = ["target"]  # the module fixture, shared with the language-model oracle's tests

NO_ROUTE = (QuestionType.ATTRIBUTE, QuestionType.DISAMBIGUATION, QuestionType.OTHER)
YES = ("Yes.", "Yes, that is the one.", "Yes, this is it.")


def test_the_refusal_is_the_papers_cannot_answer_text() -> None:
    assert TYPE_REFUSAL == "Sorry, I cannot answer your question now."


def _episode(sim: Simulator, target: ObjectInstance) -> Episode:
    return iign_episode(sim, target, "ablation-test")


def test_a_refused_type_spends_its_turn_and_is_marked_in_the_record(
    scenes: SceneCache, sim: Simulator, target: ObjectInstance
) -> None:
    oracle = RuleOracle(seed=7, question_types=NO_ROUTE)
    env = NavigationEnv([_episode(sim, target)], TaskConfig(dialog_budget=2), scenes, oracle)
    env.reset(options={"episode_index": 0})
    observation, *_ = env.step(Talk("Which way should I go?"))
    assert observation["oracle_answer"] == TYPE_REFUSAL
    observation, *_ = env.step(Talk("What colour is it?"))
    assert target.attributes.color in observation["oracle_answer"]
    observation, *_ = env.step(Talk("What colour is it?"))
    assert observation["oracle_answer"] == REFUSAL_MESSAGE  # two turns spent, the refusal's too
    record = env.record("test")
    turns = [(t.question_type, t.answered, t.type_refused) for t in record.dialog]
    assert turns == [("route", True, True), ("attribute", True, False), ("refused", False, False)]
    written = record.to_json()
    assert [("type_refused" in turn) for turn in written["dialog"]] == [True, False, False]
    assert EpisodeRecord.from_json(written) == record


def test_plain_and_cues_differ_only_in_disambiguation_answers(
    sim: Simulator, target: ObjectInstance
) -> None:
    plain, cues = RuleOracle(seed=4, cues=False), RuleOracle(seed=4, cues=True)
    for oracle in (plain, cues):
        oracle.start(context(sim, target))
    states = _states(sim, 12, seed=9)
    cued = 0
    for state in states:
        frame = sim.render(state)
        for text in QUESTIONS:
            asked = Question(text, state, frame)
            mine, theirs = plain.answer(asked), cues.answer(asked)
            assert mine.question_type == theirs.question_type
            if mine.question_type == QuestionType.DISAMBIGUATION:
                assert mine.answer in YES + PLAIN_NO, mine.answer
                if theirs.answer.startswith("Yes"):
                    assert mine.answer == theirs.answer
                cued += mine.answer != theirs.answer
            else:
                assert mine.answer == theirs.answer
    assert cued > 0  # a same-category object in view: cues say how the target differs


def test_the_llm_oracle_refuses_a_type_its_model_classifies_as_not_allowed(
    sim: Simulator, target: ObjectInstance
) -> None:
    with chat_server([completion("route"), completion("Go left.")]) as server:
        settings = OpenAISettings(model="m", base_url=server.base_url, timeout_s=2.0)
        client = OpenAIChatClient(settings, rng=np.random.default_rng(0))
        oracle = LLMOracle(client, seed=3, fallback=RuleOracle(3, question_types=NO_ROUTE))
        oracle.start(context(sim, target))
        reply = oracle.answer(question(sim, "Where should I head?"))
    assert (reply.answer, reply.question_type) == (TYPE_REFUSAL, QuestionType.ROUTE)
    assert reply.type_refused and not reply.fallback
    assert len(server.requests) == 1  # classified, never worded


def test_one_default_oracle_for_eval_data_and_the_rule_oracle() -> None:
    """Training data hear the oracle vlln eval plays with by default: the paper's plain
    disambiguation answers. A build that heard cues taught a model answers eval never gives."""
    settings = EvalConfig(agent="random", task="iign").oracle_settings()
    assert settings == OracleSettings()
    assert settings.disambiguation == Disambiguation.PLAIN
    assert not RuleOracle().cues
