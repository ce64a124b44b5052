"""The human oracle inside the real environment: an answer typed in time, and the rule
oracle standing in (recorded as a fallback) when none comes."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator

import pytest

from vlln.tasks.env import NavigationEnv
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import Talk, TaskConfig
from vlln.web.human_oracle import AnswerBoard, HumanOracle

from .conftest import SCENE_ID, Study


@pytest.fixture(scope="module")
def scenes() -> Iterator[SceneCache]:
    cache = SceneCache()
    yield cache
    cache.close()


def _env(study: Study, scenes: SceneCache, oracle: HumanOracle) -> NavigationEnv:
    env = NavigationEnv([study.episodes[0]], TaskConfig(), scenes, oracle)
    env.reset(options={"episode_index": 0})
    return env


def test_a_typed_answer_reaches_the_navigator(study: Study, scenes: SceneCache) -> None:
    board = AnswerBoard()
    env = _env(study, scenes, HumanOracle(board, time_limit_s=30.0))

    def person() -> None:
        while board.pending() is None:
            time.sleep(0.01)
        pending = board.pending()
        assert pending is not None and pending.text == "Which way should I go?"
        assert not board.give(pending.number + 1, "wrong question")
        assert board.give(pending.number, "Behind you.")

    helper = threading.Thread(target=person)
    helper.start()
    observation, *_ = env.step(Talk("Which way should I go?"))
    helper.join()
    assert observation["oracle_answer"] == "Behind you."
    turn = env.record("human").dialog[0]
    assert turn.backend == "human" and turn.answered and not turn.fallback
    assert turn.question_type == "route"


def test_no_answer_in_time_lets_the_rule_oracle_answer(study: Study, scenes: SceneCache) -> None:
    board = AnswerBoard()
    env = _env(study, scenes, HumanOracle(board, time_limit_s=0.2))
    observation, *_ = env.step(Talk("What color is it?"))
    turn = env.record("human").dialog[0]
    assert turn.fallback and turn.backend == "human" and turn.question_type == "attribute"
    target = scenes.get(SCENE_ID).house.instance(study.target_ids[0])
    assert target.attributes.color in observation["oracle_answer"]  # the rule oracle knows it
    assert board.pending() is None and not board.give(1, "too late")
