"""``vlln bench oracle-answers``: an oracle's answers to a file of questions, each asked in a
real episode, for readers to judge whether each answer fits its question
(docs/helpful-oracle.md).

Each question is asked in an IIGN episode of the small test houses whose target is of the
question's category, after the FBE agent (true detector) has explored a seeded number of
steps, so it is asked where a searching agent stands, through the environment's own TALK.

    vlln bench oracle-answers QUESTIONS.jsonl --oracle helpful --out A.jsonl

A question line is ``{"question": ..., "kind": ..., "category": ...}``; an answer line adds
the episode, the steps walked, the answer, its question type and the kind of help it gave.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from typing import Any

import numpy as np

from vlln.agents.protocol import Agent
from vlln.agents.registry import make_agent
from vlln.bench.settings import OracleAnswersBench
from vlln.errors import DataFormatError
from vlln.files import ReadCap, parse_json, write_text_atomic
from vlln.oracle.settings import OracleBackend, OracleSettings
from vlln.tasks.env import NavigationEnv
from vlln.tasks.episode import Episode
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import Talk, TaskConfig, TaskType
from vlln.tasks.split_files import default_cache_dir, load_or_build_split
from vlln.world.catalogue.aliases import ALIASES

MAX_WALK = 60  # the most steps explored before the question is asked
# A question set is hundreds of short lines.
QUESTIONS_CAP = ReadCap("a question file", 16)


def matching_episodes(episodes: Sequence[Episode], category: str) -> list[Episode]:
    """The episodes whose target is of ``category`` (a catalogue alias counts: "sofa" is a
    couch); all of them when none is."""
    names = {category.lower(), ALIASES.get(category.lower(), "")}
    found = [e for e in episodes if (e.object_category or "").lower() in names]
    found = found or [
        e for e in episodes if category.lower() in (e.object_category or "").lower().split()
    ]
    return found or list(episodes)


def answer_questions(
    questions: Sequence[dict[str, Any]],
    backend: OracleBackend,
    episodes: Sequence[Episode],
    seed: int = 0,
) -> list[dict[str, Any]]:
    """One answer line per question (module doc)."""
    scenes = SceneCache()
    settings = OracleSettings(backend=backend)
    rows = []
    try:
        for index, question in enumerate(questions):
            rng = np.random.default_rng([seed, index])
            candidates = matching_episodes(episodes, str(question["category"]))
            episode = candidates[int(rng.integers(len(candidates)))]
            env = NavigationEnv(
                [episode],
                TaskConfig(task=TaskType.IIGN),
                scenes,
                settings.make(seed + index),
                privileged=True,
            )
            walked = _walk(env, make_agent("fbe", seed + index, "truth"), rng)
            env.step(Talk(str(question["question"])))
            turn = env.record("blind").dialog[-1]
            rows.append(
                {
                    **question,
                    "episode_id": episode.episode_id,
                    "scene_id": episode.scene_id,
                    "target_category": episode.object_category,
                    "steps_walked": walked,
                    "answer": turn.answer,
                    "question_type": turn.question_type,
                    "help_kind": turn.help_kind,
                }
            )
    finally:
        scenes.close()
    return rows


def _walk(env: NavigationEnv, agent: Agent, rng: np.random.Generator) -> int:
    """Start the episode and explore a drawn number of steps; an exploration that ends the
    episode first is replayed to the step before its end. Returns the steps walked."""
    observation, _ = env.reset(options={"episode_index": 0})
    agent.reset(env.episode_info())
    actions = []
    for _ in range(int(rng.integers(MAX_WALK + 1))):
        action = agent.act(observation)
        observation, _, done, truncated, _ = env.step(action)
        actions.append(action)
        if done or truncated:
            env.reset(options={"episode_index": 0})
            actions.pop()
            for earlier in actions:
                env.step(earlier)
            break
    return len(actions)


def run_oracle_answers(settings: OracleAnswersBench) -> None:
    """Ask every question of ``settings.questions`` and write the answer lines."""
    text = QUESTIONS_CAP.read(settings.questions).decode("utf-8", errors="replace")
    questions = []
    for number, line in enumerate(text.splitlines(), 1):
        if not line.strip():
            continue
        try:
            question = parse_json(line)
        except DataFormatError as error:
            question = str(error)
        if not isinstance(question, dict) or not {"question", "category"} <= question.keys():
            raise DataFormatError(
                f"{settings.questions}:{number} is not a question line; write each as "
                '{"question": ..., "kind": ..., "category": ...}'
            )
        questions.append(question)
    cache = settings.cache_dir or default_cache_dir()
    episodes = load_or_build_split("test", "iign", settings.houses, cache, progress=False)
    rows = answer_questions(questions, OracleBackend(settings.oracle), episodes, settings.seed)
    write_text_atomic(settings.out, "".join(json.dumps(row) + "\n" for row in rows))
    print(f"{len(rows)} answers in {settings.out}")
