"""The rule oracle as a whole: protocol, errors, determinism and its use by the environment."""

from __future__ import annotations

import numpy as np
import pytest

from tests.oracle.episodes import iign_episode
from vlln.errors import ConfigError
from vlln.oracle.classify import classify_question
from vlln.oracle.rule_oracle import RuleOracle
from vlln.sim.agent import AgentState
from vlln.sim.simulator import Simulator
from vlln.sim.viewpoints import view_points
from vlln.tasks.env import NavigationEnv
from vlln.tasks.oracle_protocol import EpisodeContext, Oracle, Question
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import REFUSAL_MESSAGE, Talk, TaskConfig
from vlln.world.model import ObjectInstance

QUESTIONS = (
    "What color is it?",
    "Which room is it in?",
    "Describe it.",
    "Which way should I go?",
    "How do I get there?",
    "What should I do next?",
    "Is this the one?",
    "How far is it?",
    "Am I close?",
    "What time is it?",
)


def _targets(sim: Simulator, count: int) -> list[ObjectInstance]:
    component = sim.grid.largest_component()
    found = []
    for inst in sim.house.instances:
        goals = view_points(sim.grid, inst.box)
        if inst.attributes.color and any(sim.grid.component_of(*g) == component for g in goals):
            found.append(inst)
    return found[:count]


def _context(sim: Simulator, target: ObjectInstance) -> EpisodeContext:
    return EpisodeContext(sim, target, tuple(view_points(sim.grid, target.box)))


def _states(sim: Simulator, n: int, seed: int) -> list[AgentState]:
    rng = np.random.default_rng(seed)
    component = sim.grid.largest_component()
    return [
        AgentState(_on_floor(sim.grid.sample_navigable_point(rng, component)), 0.0)
        for _ in range(n)
    ]


def _on_floor(point: tuple[float, float]) -> tuple[float, float, float]:
    return (point[0], 0.0, point[1])


def _dialog(oracle: RuleOracle, sim: Simulator, states: list[AgentState]) -> list[str]:
    answers: list[str] = []
    for state in states:
        frame = sim.render(state)
        answers.extend(oracle.answer(Question(q, state, frame)).answer for q in QUESTIONS)
    return answers


def test_rule_oracle_satisfies_the_protocol(sim: Simulator) -> None:
    oracle: Oracle = RuleOracle()
    target = _targets(sim, 1)[0]
    oracle.start(_context(sim, target))
    state = _states(sim, 1, 0)[0]
    reply = oracle.answer(Question("What color is it?", state, sim.render(state)))
    assert target.attributes.color in reply.answer


def test_reply_types_are_the_classified_types(sim: Simulator) -> None:
    oracle = RuleOracle()
    oracle.start(_context(sim, _targets(sim, 1)[0]))
    state = _states(sim, 1, 1)[0]
    frame = sim.render(state)
    for question in QUESTIONS:
        reply = oracle.answer(Question(question, state, frame))
        assert reply.question_type == classify_question(question)
        assert reply.answer


def test_same_seed_same_words_and_seeds_vary_the_wording(sim: Simulator) -> None:
    target = _targets(sim, 1)[0]
    states = _states(sim, 3, 2)
    dialogs = []
    for seed in (0, 0, 1, 2, 3):
        oracle = RuleOracle(seed)
        oracle.start(_context(sim, target))
        dialogs.append(_dialog(oracle, sim, states))
    assert dialogs[0] == dialogs[1]
    assert any(d != dialogs[0] for d in dialogs[2:])
    # Restarting the episode restarts its paraphrase sequence.
    again = RuleOracle(0)
    again.start(_context(sim, _targets(sim, 2)[1]))
    again.start(_context(sim, target))
    assert _dialog(again, sim, states) == dialogs[0]


def test_a_new_episode_answers_about_its_own_target(sim: Simulator) -> None:
    first, second = _targets(sim, 2)
    oracle = RuleOracle()
    state = _states(sim, 1, 3)[0]
    frame = sim.render(state)
    for target in (first, second, first):
        oracle.start(_context(sim, target))
        reply = oracle.answer(Question("What kind of object is it exactly?", state, frame))
        assert (target.fine_category or target.category) in reply.answer


def test_misuse_raises_config_errors(sim: Simulator) -> None:
    for seed in (-1, 1.5, True, "0"):
        with pytest.raises(ConfigError, match="seed"):
            RuleOracle(seed)  # type: ignore[arg-type]
    with pytest.raises(ConfigError, match="goal_radius"):
        RuleOracle(goal_radius=0.0)
    oracle = RuleOracle()
    state = _states(sim, 1, 4)[0]
    with pytest.raises(ConfigError, match="start"):
        oracle.answer(Question("What color is it?", state, sim.render(state)))
    target = _targets(sim, 1)[0]
    with pytest.raises(ConfigError, match="view points"):
        oracle.start(EpisodeContext(sim, target, ()))


def test_the_environment_asks_the_oracle_and_enforces_the_budget(
    scenes: SceneCache, sim: Simulator
) -> None:
    target = _targets(sim, 1)[0]
    episode = iign_episode(sim, target, "oracle-test")
    x, _, z = episode.start_position
    env = NavigationEnv([episode], TaskConfig(dialog_budget=2), scenes, RuleOracle(seed=7))
    env.reset(options={"episode_index": 0})
    observation, *_ = env.step(Talk("What colour is it?"))
    assert target.attributes.color in observation["oracle_answer"]
    observation, *_ = env.step(Talk("How far is it?"))
    metres = env.field.distance(x, z)
    expected = "less than a meter" if metres < 1.0 else f"about {round(metres)} meter"
    assert expected in observation["oracle_answer"], (observation["oracle_answer"], metres)
    observation, *_ = env.step(Talk("Is this the one?"))
    assert observation["oracle_answer"] == REFUSAL_MESSAGE
    kinds = [turn.question_type for turn in env.record("test").dialog]
    assert kinds == ["attribute", "other", "refused"]
