"""The frontier agent's asking decision as a Gymnasium environment (:class:`DialogEnv`).

Datasheet
---------
* **Episode**: one IIGN navigation episode played by the frontier agent, which navigates by
  itself and pauses at each of its dialog decision points (:mod:`vlln.agents.frontier.asking`).
* **Observation**: ``Box(0, 1, (18,), float32)``, the agent's belief at the point
  (:data:`~vlln.agents.frontier.asking.FEATURES`).
* **Action**: ``Discrete(4)``: 0 walk on, 1 ask the colour, 2 ask the way, 3 ask "is this
  the one?"; a kind that is not allowed at the point walks on.
* **Reward**: −λ for each question asked, when it is asked, and 1 at the end if the episode
  succeeded: per episode, success − λ × questions.
* **Episodes**: a split's houses other than the test houses (the test split and ``test500``
  are refused), house by house in an order drawn from ``seed``, each house's episodes
  shuffled; the agent and oracle of an episode are seeded as ``vlln eval`` seeds them. An
  episode without a decision point is played and skipped.
* **Info**: on the last step ``record``, the episode record (:class:`EpisodeRecord`).

The navigation runs in one worker thread (every OpenGL call stays in it), handing each decision
to the caller of :meth:`DialogEnv.step` and waiting for the answer.
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import gymnasium
import numpy as np
from numpy.typing import NDArray

from vlln.agents.frontier import FrontierAgent
from vlln.agents.frontier.asking import ACTIONS, FEATURES, Decision
from vlln.errors import ConfigError, EpisodeRefusedError
from vlln.eval.play import episode_seed, play_episode
from vlln.oracle.rule_oracle import RuleOracle
from vlln.tasks.env import NavigationEnv
from vlln.tasks.episode import Episode
from vlln.tasks.metrics import success
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import DEFAULT_MAX_STEPS, TaskConfig, TaskType
from vlln.tasks.split_files import default_cache_dir, load_or_build_split
from vlln.tasks.splits import SPLIT_SIZES, TEST_PROTOCOL_SOURCE, source_split

_ABORT = -1  # the answer that ends the episode in play
_Item = tuple["_Handoff", Decision] | EpisodeRecord | BaseException
"""What the worker hands over: a decision to answer, a finished episode, or its failure."""


class _Aborted(Exception):
    """Raised inside the agent to end an episode the caller left."""


class _Handoff:
    """The dialog policy of the driven agent: each decision goes out, its answer comes back."""

    def __init__(self, explore_every: int, out: queue.Queue[_Item]) -> None:
        self._every = explore_every
        self.out = out
        self.answers: queue.Queue[int] = queue.Queue()

    @property
    def explore_every(self) -> int:
        return self._every

    def choose(self, decision: Decision) -> str | None:
        self.out.put((self, decision))
        answer = self.answers.get()
        if answer == _ABORT:
            raise _Aborted
        return decision.action(answer)


def training_episodes(
    split: str, houses: int | None, preset: str, cache_dir: Path | None = None
) -> list[Episode]:
    """The IIGN episodes of a split's houses; the test houses are refused."""
    if source_split(split) == TEST_PROTOCOL_SOURCE or split not in SPLIT_SIZES:
        raise ConfigError(f"train on the train or val split, never on {split!r}")
    count = houses or SPLIT_SIZES[split]
    folder = cache_dir or default_cache_dir()
    return load_or_build_split(split, TaskType.IIGN, count, folder, progress=False, preset=preset)


class DialogEnv(gymnasium.Env[NDArray[np.float32], np.int64]):
    """When to ask, over whole navigation episodes of the frontier agent (module datasheet)."""

    def __init__(
        self,
        episodes: list[Episode],
        lam: float = 0.05,
        seed: int = 0,
        detector: str = "noisy",
        budget: int = 5,
        explore_every: int = 20,
        max_steps: int = DEFAULT_MAX_STEPS,
        scenes: Callable[[], SceneCache] = SceneCache,
    ) -> None:
        if not episodes:
            raise ConfigError("the dialog environment needs at least one episode")
        self.observation_space = gymnasium.spaces.Box(0.0, 1.0, (len(FEATURES),), np.float32)
        self.action_space = gymnasium.spaces.Discrete(len(ACTIONS))
        self.lam = float(lam)
        self.episodes = episodes
        self._seed = int(seed)
        self._detector = detector
        self._explore_every = explore_every
        self._scenes = scenes  # called in the worker, where its simulators then render
        self._task = TaskConfig(task=TaskType.IIGN, max_steps=max_steps, dialog_budget=budget)
        self._items: queue.Queue[_Item] = queue.Queue()
        self._handoff: _Handoff | None = None  # of the decision awaiting an answer
        self._last: Decision | None = None
        self._worker: threading.Thread | None = None
        self._stopping = False
        self._playing = False  # whether the caller is inside an episode
        self.played = 0  # navigation episodes finished by the worker

    # ----------------------------------------------------------------- Gymnasium API
    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[NDArray[np.float32], dict[str, Any]]:
        super().reset(seed=seed)
        if self._worker is None:
            if seed is not None:
                self._seed = seed
            self._worker = threading.Thread(target=self._run, daemon=True)
            self._worker.start()
        if self._playing:
            self._answer(_ABORT)
            while not isinstance(self._next(), EpisodeRecord):
                pass
        while True:
            item = self._next()
            if isinstance(item, Decision):
                self._playing = True
                return item.features(), {}

    def step(
        self, action: np.int64 | int
    ) -> tuple[NDArray[np.float32], float, bool, bool, dict[str, Any]]:
        decision = self._last
        if not self._playing or decision is None:
            raise ConfigError("call reset() before step()")
        asked = decision.action(int(action)) is not None
        self._answer(int(action))
        reward = -self.lam if asked else 0.0
        item = self._next()
        if isinstance(item, Decision):
            return item.features(), reward, False, False, {}
        self._playing = False
        reward += float(success(item))
        return decision.features(), reward, True, False, {"record": item}

    def close(self) -> None:
        """Stop the worker: the episode in play ends, the houses are closed."""
        if self._worker is None:
            return
        self._stopping = True
        self._answer(_ABORT)
        while self._worker.is_alive():
            try:
                item = self._items.get(timeout=0.1)
            except queue.Empty:
                continue
            if isinstance(item, tuple):
                item[0].answers.put(_ABORT)
        self._worker = None
        self._playing = False

    # ----------------------------------------------------------------- the worker
    def _next(self) -> Decision | EpisodeRecord:
        """The worker's next decision or finished episode; its failure is raised here."""
        item = self._items.get()
        if isinstance(item, BaseException):
            raise item
        if isinstance(item, tuple):
            self._handoff, self._last = item
            return item[1]
        return item

    def _answer(self, action: int) -> None:
        if self._handoff is not None:
            self._handoff.answers.put(action)
            self._handoff = None

    def _order(self) -> Iterator[Episode]:
        """Episodes house by house, houses and their episodes shuffled anew each pass."""
        rng = np.random.default_rng(self._seed)
        by_house: dict[str, list[Episode]] = {}
        for episode in self.episodes:
            by_house.setdefault(episode.scene_id, []).append(episode)
        houses = sorted(by_house)
        while True:
            for k in rng.permutation(len(houses)):
                group = by_house[houses[k]]
                for j in rng.permutation(len(group)):
                    yield group[j]

    def _run(self) -> None:
        scenes = self._scenes()
        try:
            for episode in self._order():
                if self._stopping:
                    return
                try:
                    self._items.put(self._play(episode, scenes))
                except EpisodeRefusedError:
                    continue  # its start or goals are unreachable: eval skips it too
                self.played += 1
        except Exception as error:
            self._items.put(error)
        finally:
            scenes.close()

    def _play(self, episode: Episode, scenes: SceneCache) -> EpisodeRecord:
        """One episode; a decision the caller leaves ends it as an error inside the agent."""
        handoff = _Handoff(self._explore_every, self._items)
        agent = FrontierAgent(
            episode_seed(self._seed, "agent", episode),
            detector=self._detector,
            dialog_policy=handoff,
        )
        oracle = RuleOracle(episode_seed(self._seed, "oracle", episode))
        env = NavigationEnv([episode], self._task, scenes, oracle, privileged=True)
        return play_episode(env, agent, agent.name)
