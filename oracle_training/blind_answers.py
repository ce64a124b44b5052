"""An oracle's answers to a file of questions, each asked in a real episode, for readers to
judge whether each answer fits its question (docs/helpful-oracle.md).

Each question is asked in an IIGN episode of the small test houses whose target is of the
question's category, after the FBE agent (true detector) has explored a seeded number of
steps, so it is asked where a searching agent stands, through the environment's own TALK.

    python -m oracle_training.blind_answers QUESTIONS.jsonl --oracle helpful --out A.jsonl

A question line is ``{"question": ..., "kind": ..., "category": ...}``; an answer line adds
the episode, the steps walked, the answer, its question type and the kind of help it gave.
"""

from __future__ import annotations

import argparse
import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from vlln.agents.protocol import Agent
from vlln.agents.registry import make_agent
from vlln.files import write_text_atomic
from vlln.oracle.settings import OracleBackend, OracleSettings
from vlln.tasks.env import NavigationEnv
from vlln.tasks.episode import Episode
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import Talk, TaskConfig, TaskType
from vlln.tasks.split_files import load_or_build_split
from vlln.world.catalogue.aliases import ALIASES

MAX_WALK = 60  # the most steps explored before the question is asked


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


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("questions", type=Path)
    parser.add_argument("--oracle", default="helpful", choices=[b.value for b in OracleBackend])
    parser.add_argument("--out", type=Path, required=True)
    parser.add_argument("--houses", type=int, default=4, help="small test houses")
    parser.add_argument("--cache", type=Path, default=Path("out/blind-cache"))
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    questions = [json.loads(line) for line in args.questions.read_text().splitlines() if line]
    episodes = load_or_build_split("test", "iign", args.houses, args.cache, progress=False)
    rows = answer_questions(questions, OracleBackend(args.oracle), episodes, args.seed)
    write_text_atomic(args.out, "".join(json.dumps(row) + "\n" for row in rows))
    print(f"{len(rows)} answers in {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
