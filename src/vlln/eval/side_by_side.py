"""Episodes played side by side in one process, their model calls answered in batches
(``vlln eval --agent vlln --concurrent N``).

A model's forward pass on a GPU answers several conversations in about the time of one, so N
episodes that each wait for the model most of their time finish nearly N times sooner when
their calls are batched. Here N threads take the plan's episodes in order, each with its own
scene cache (a simulator holds one agent's pose), and the ``vlln`` agent of every episode
sends its calls to one :class:`~vlln.agents.local.batching.ThreadedBatching`.

Only one thread runs episode code at a time (the *turn*): a thread gives the turn up while it
waits for the model and takes it back with the reply. So simulators, oracles and every cache
behind them are never used by two threads at once, while the model works for several
episodes at once and the next episode renders while the model thinks. Records are those of
one-at-a-time play: every episode's agent and oracle are seeded from the episode alone
(:mod:`vlln.eval.play`) and greedy decoding with left padding gives each call the reply it
gets alone. Results go back to the runner in plan order; an episode finished before an
earlier one waits for it, so a killed run loses at most the episodes in play, as before.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator, Sequence
from functools import lru_cache, partial

from vlln.agents.local.backend import load_backend
from vlln.agents.local.batching import BatchingModel, ThreadedBatching
from vlln.agents.local.options import VllnOptions
from vlln.agents.model.agent import ModelAgent
from vlln.agents.model.backend import ModelReply, VisionLanguageModel
from vlln.agents.protocol import Agent
from vlln.errors import ConfigError
from vlln.eval.config import EvalConfig
from vlln.eval.play import GroupPlayer, OracleFactory, Played, WorkItem, by_episode, group_player
from vlln.prompt import Conversation
from vlln.tasks.scenes import SceneCache, scene_house

BATCHED_AGENTS = ("vlln",)
"""Agents whose model calls are batched, so that playing episodes side by side pays."""


def check_concurrent(config: EvalConfig, concurrent: int) -> None:
    """Refuse side-by-side play for agents without a batched model, in one line."""
    if concurrent < 1:
        raise ConfigError(f"--concurrent must be at least 1, got {concurrent}")
    if concurrent > 1 and config.agent not in BATCHED_AGENTS:
        raise ConfigError(
            f"--concurrent {concurrent} batches the model calls of --agent vlln; "
            f"{config.agent} plays one episode at a time (drop --concurrent)"
        )


class _WaitingModel:
    """``model`` called with the turn given up for the wait (module doc)."""

    def __init__(self, model: ThreadedBatching, turn: threading.Lock) -> None:
        self.model = model
        self.turn = turn

    @property
    def backend(self) -> str:
        return self.model.backend

    def generate(self, conversation: Conversation, images: Sequence[bytes]) -> ModelReply:
        self.turn.release()
        try:
            return self.model.generate(conversation, images)
        finally:
            self.turn.acquire()


def _agent_on(model: VisionLanguageModel, name: str, seed: int, _detector: str | None) -> Agent:
    return ModelAgent(model, seed, name=name)


def play_side_by_side(
    items: Sequence[WorkItem],
    config: EvalConfig,
    concurrent: int,
    scenes: SceneCache | None = None,
    oracle_factory: OracleFactory | None = None,
    sweep: bool = True,
    on_model_stats: Callable[[BatchingModel], None] | None = None,
) -> Iterator[list[Played]]:
    """What each episode of ``items`` came to, in order, ``concurrent`` of them in play at
    once (module doc); ``scenes`` serves the first thread (the others make their own), and
    ``on_model_stats`` hears at the end how the model's calls were batched."""
    check_concurrent(config, concurrent)
    options = config.agent_options
    assert isinstance(options, VllnOptions)
    backend = load_backend(options.model_dir, options.device, options.max_tokens)
    groups = by_episode(items)
    with ThreadedBatching(backend, max_batch=concurrent) as model:
        turn = threading.Lock()  # the right to run episode code (module doc)
        factory = partial(_agent_on, _WaitingModel(model, turn))
        play = group_player(config, factory, oracle_factory, sweep)
        side_by_side = _SideBySide(groups, play, model, turn, concurrent, scenes, config.scenes)
        yield from side_by_side.results()
        if on_model_stats is not None:
            on_model_stats(model.model)


class _SideBySide:
    """The threads playing ``groups`` and the results they have handed in."""

    def __init__(
        self,
        groups: list[list[WorkItem]],
        play: GroupPlayer,
        model: ThreadedBatching,
        turn: threading.Lock,
        threads: int,
        scenes: SceneCache | None,
        scenes_dir: str | None,
    ) -> None:
        self.groups, self.play, self.model, self.turn = groups, play, model, turn
        self.done: dict[int, list[Played] | BaseException] = {}
        self.taken = 0  # groups handed to a thread so far
        self.stopping = False
        self.changed = threading.Condition()
        count = min(threads, len(groups))
        houses = lru_cache(maxsize=2)(scene_house)  # each house built once for all threads
        new = partial(SceneCache, scenes_dir=scenes_dir, houses=houses)
        self.caches = [scenes or new()] + [new() for _ in range(count - 1)]
        self.own = self.caches if scenes is None else self.caches[1:]
        self.threads = [
            threading.Thread(
                target=self._work, args=(cache,), name=f"vlln-episodes-{n}", daemon=True
            )
            for n, cache in enumerate(self.caches[:count])
        ]

    def results(self) -> Iterator[list[Played]]:
        """Each group's results in order, as soon as it and every earlier one are in; an
        error of a group is raised at its place."""
        for _ in self.threads:
            self.model.join()  # before any thread calls, so the first batch waits for all
        for thread in self.threads:
            thread.start()
        try:
            for index in range(len(self.groups)):
                with self.changed:
                    self.changed.wait_for(partial(self.done.__contains__, index))
                    result = self.done.pop(index)
                if isinstance(result, BaseException):
                    raise result
                yield result
        except KeyboardInterrupt:  # a killed run does not wait for the episodes in play
            self._stop(wait=False)
            raise
        except BaseException:
            self._stop(wait=True)
            raise
        self._stop(wait=True)

    def _stop(self, wait: bool) -> None:
        """No group is taken any more; with ``wait``, the threads' last ones are played out
        and their scene caches closed."""
        with self.changed:
            self.stopping = True
        if wait:
            for thread in self.threads:
                thread.join()
            for cache in self.own:
                cache.close()

    def _work(self, scenes: SceneCache) -> None:
        """Play the next group not yet taken until none is left (or the run stops), then
        leave the model's callers (joined for this thread by :meth:`results`)."""
        try:
            with self.turn:
                scene: str | None = None
                while (index := self._take()) is not None:
                    group = self.groups[index]
                    if scene is not None and group[0].episode.scene_id != scene:
                        scenes.close()  # the plan never returns to a scene it has left
                    scene = group[0].episode.scene_id
                    result: list[Played] | BaseException
                    try:
                        result = self.play(group, scenes)
                    except BaseException as error:  # handed to the runner at its place
                        result = error
                    with self.changed:
                        self.done[index] = result
                        self.changed.notify_all()
        finally:
            self.model.leave()

    def _take(self) -> int | None:
        """The index of the next group to play, or None when there is none (or the run
        stops)."""
        with self.changed:
            if self.stopping or self.taken == len(self.groups):
                return None
            self.taken += 1
            return self.taken - 1
