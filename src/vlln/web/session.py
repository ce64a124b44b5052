"""One episode played in the browser: a navigator, an oracle, and a thread that owns them.

Each session runs on its own thread with its own simulator, because a person's question to
another person may keep the navigator waiting for a minute and must not hold up anyone else
(and an OpenGL context stays on the thread that uses it). A human navigator's actions arrive
as commands on a queue; an agent navigator acts by itself once its human oracle has joined.
Everything that happens is journaled (:mod:`vlln.web.journal`) before the pages hear of it,
and the finished episode is handed to ``finish``, which writes its record.
"""

from __future__ import annotations

import contextlib
import queue
import threading
from collections import deque
from collections.abc import Callable
from concurrent.futures import Future
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from vlln.agents.protocol import Agent, reported_stop_reason
from vlln.agents.registry import make_agent
from vlln.eval.play import derive_seed
from vlln.eval.results import RecordKey
from vlln.sim.agent import Action
from vlln.tasks.env import NavigationEnv, Observation
from vlln.tasks.episode import Episode
from vlln.tasks.oracle_protocol import EpisodeContext, Oracle, Question, Reply
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import AgentOutput, Talk, TaskConfig
from vlln.web.changes import ChangeSignal
from vlln.web.config import OracleKind, WebConfig, navigator_label
from vlln.web.human_oracle import AnswerBoard
from vlln.web.journal import Journal, SessionSpec, Step
from vlln.world.model import House, ObjectInstance

OracleFactory = Callable[[OracleKind, int, AnswerBoard], Oracle]
Finish = Callable[["EpisodeSession", EpisodeRecord], None]
_SHUTDOWN = object()
_LEAVE = object()  # the navigator ends the session
LEFT = "the navigator ended the session"


class Status:
    STARTING = "starting"
    WAITING_FOR_ORACLE = "waiting for the oracle to join"
    PLAYING = "playing"
    ANSWERING = "waiting for the answer"
    FINISHED = "finished"
    ABANDONED = "abandoned"


class _SessionOracle:
    """The session's oracle: hands out journaled replies first (a resumed episode), then asks
    the live oracle; keeps the last reply for the journal."""

    def __init__(self, live: Oracle, replayed: list[Reply]) -> None:
        self.live = live
        self.replayed = deque(replayed)
        self.last: Reply | None = None

    def start(self, context: EpisodeContext) -> None:
        self.live.start(context)

    def answer(self, question: Question) -> Reply:
        self.last = self.replayed.popleft() if self.replayed else self.live.answer(question)
        return self.last


@dataclass
class View:
    """What the pages show, updated by the session thread after every change."""

    status: str = Status.STARTING
    rgb: np.ndarray | None = None
    frame_number: int = 0
    steps: int = 0
    questions_left: int = 0
    dialog: list[tuple[str, str, bool]] = field(default_factory=list)
    trail: list[tuple[float, float]] = field(default_factory=list)
    pose: tuple[float, float, float] = (0.0, 0.0, 0.0)
    # The navigator's storey and that of every trail point; None in a house with one storey.
    storey: int | None = None
    trail_storeys: list[int | None] = field(default_factory=list)
    success: bool | None = None
    end_reason: str | None = None
    error: str | None = None


class EpisodeSession:
    """One episode of one pairing (module doc)."""

    def __init__(
        self,
        spec: SessionSpec,
        episode: Episode,
        config: WebConfig,
        journal: Journal,
        make_oracle: OracleFactory,
        finish: Finish,
        signal: ChangeSignal,
        replay: list[Step] | None = None,
        abandon_after_replay: str | None = None,
    ) -> None:
        self.spec = spec
        self.episode = episode
        self.config = config
        self.oracle_kind = OracleKind(spec.oracle)
        self.label = navigator_label(spec.navigator, self.oracle_kind)
        self.signal = signal
        self.board = AnswerBoard(signal.bump)
        self.view = View()
        self.lock = threading.Lock()
        self._journal = journal
        self._make_oracle = make_oracle
        self._finish = finish
        self._replay = list(replay or [])
        self._abandon_after_replay = abandon_after_replay
        self._env: NavigationEnv | None = None
        self.ready = threading.Event()  # set once the house and target are known
        self.house: House | None = None
        self.target: ObjectInstance | None = None
        self.frame_cache: tuple[tuple[str, int], str] | None = None  # JPEG of the last frame
        self.map_cache: dict[int | None, dict[str, Any]] = {}  # the map of each storey
        self._commands: queue.Queue[tuple[object, Future[None]]] = queue.Queue(maxsize=4)
        self._oracle_joined = threading.Event()
        self._closing = False
        self._thread = threading.Thread(
            target=self._main, name=f"vlln-web-{spec.session_id}", daemon=True
        )

    # ------------------------------------------------------------ control from other threads
    def start(self) -> None:
        self._thread.start()

    @property
    def key(self) -> RecordKey:
        """The key its record will have (see :func:`vlln.eval.results.record_key`)."""
        spec = self.spec
        task = self.config.task.value
        return (self.label, task, spec.budget, spec.scene_id, spec.episode_id)

    @property
    def done(self) -> bool:
        return self.view.status in (Status.FINISHED, Status.ABANDONED)

    def submit(self, output: AgentOutput) -> Future[None]:
        """Queue a human navigator's action; the future resolves once it is played.
        Raises ``queue.Full`` when actions arrive faster than they are played."""
        done: Future[None] = Future()
        self._commands.put_nowait((output, done))
        return done

    def leave(self) -> Future[None]:
        """Queue the human navigator's end of the session: it is recorded as abandoned and
        frees its slot at once, instead of after the idle limit. Raises ``queue.Full`` like
        :meth:`submit`."""
        done: Future[None] = Future()
        self._commands.put_nowait((_LEAVE, done))
        return done

    def oracle_joined(self) -> None:
        """The oracle page is open: an agent navigator may begin."""
        self._oracle_joined.set()

    def stop(self) -> None:
        """End the thread without recording: the journal keeps the episode for a restart."""
        self._closing = True
        self._oracle_joined.set()
        self.board.give_up()
        with contextlib.suppress(queue.Full):
            self._commands.put_nowait((_SHUTDOWN, Future()))
        self._thread.join(timeout=10.0)

    # ------------------------------------------------------------ the session thread
    def _main(self) -> None:
        scenes = SceneCache(capacity=1)
        try:
            self._play(scenes)
        except Exception as error:  # never lose the episode: record what happened
            if self._env is not None and not self._closing and not self.done:
                self._end(self._env.record(self.label, error=_describe(error)), Status.ABANDONED)
        finally:
            scenes.close()
            self._journal.close()

    def _play(self, scenes: SceneCache) -> None:
        spec = self.spec
        task = TaskConfig(self.config.task, self.config.max_steps, dialog_budget=spec.budget)
        options = self.config.agent_options.get(spec.navigator)
        agent = (
            None
            if spec.human_navigator
            else make_agent(spec.navigator, self._seed("agent"), options=options)
        )
        live = self._make_oracle(self.oracle_kind, self._seed("oracle"), self.board)
        replies = [step.reply for step in self._replay if step.reply is not None]
        self._oracle = _SessionOracle(live, replies)
        privileged = agent is not None and agent.privileged
        oracle = self._oracle if task.dialog_enabled else None
        env = NavigationEnv([self.episode], task, scenes, oracle, privileged=privileged)
        self._env = env
        observation, _ = env.reset(options={"episode_index": 0})
        self.house, self.target = env.sim.house, env.targets[0]
        self.ready.set()
        self._publish(observation, 0)
        for step in self._replay:
            observation, done = self._apply(_output_of(step), journal=False)
            if done:
                self._end(env.record(self.label), Status.FINISHED)
                return
        if self._abandon_after_replay is not None:
            self._abandon(self._abandon_after_replay)
        elif agent is None:
            self._serve_person()
        else:
            self._run_agent(agent, observation)

    def _serve_person(self) -> None:
        self._set_status(Status.PLAYING)
        while True:
            try:
                command, done = self._commands.get(timeout=self.config.idle_limit_s)
            except queue.Empty:
                self._abandon(f"no action for {self.config.idle_limit_s:.0f} s")
                return
            if command is _SHUTDOWN:
                return
            if command is _LEAVE:
                self._abandon(LEFT)
                done.set_result(None)
                return
            assert isinstance(command, (Action, Talk))
            try:
                _, finished = self._apply(command)
                if finished:
                    self._end(self._require_env().record(self.label), Status.FINISHED)
                    return
            finally:
                done.set_result(None)
            if self._closing:
                return

    def _run_agent(self, agent: Agent, observation: Observation) -> None:
        env = self._require_env()
        if self.oracle_kind == OracleKind.HUMAN:
            self._set_status(Status.WAITING_FOR_ORACLE)
            if not self._oracle_joined.wait(self.config.idle_limit_s):
                self._abandon(f"the oracle did not join within {self.config.idle_limit_s:.0f} s")
                return
        if self._closing:
            return
        self._set_status(Status.PLAYING)
        try:
            agent.reset(env.episode_info())
        except Exception as error:  # an agent that fails ends its episode, as in vlln eval
            self._end(env.record(self.label, error=_describe(error)), Status.FINISHED)
            return
        while not self._closing:
            try:
                output = agent.act(observation)
            except Exception as error:
                self._end(env.record(self.label, error=_describe(error)), Status.FINISHED)
                return
            observation, finished = self._apply(output)
            if finished:
                record = env.record(self.label, stop_reason=reported_stop_reason(agent))
                self._end(record, Status.FINISHED)
                return

    def _apply(self, output: object, journal: bool = True) -> tuple[Observation, bool]:
        """Play one output, journal it and publish the new view."""
        if isinstance(output, Talk):
            self._set_status(Status.ANSWERING)
            self._oracle.last = None
        observation, _, terminated, truncated, info = self._require_env().step(output)  # type: ignore[arg-type]
        if self._closing:  # a shutdown cut the wait for an answer short: replay it later
            return observation, False
        if journal:
            if isinstance(output, Talk):
                self._journal.talk(output.text, self._oracle.last)
            elif isinstance(output, Action):
                self._journal.action(output.name)
            else:
                self._journal.invalid(str(output)[:80])
        if isinstance(output, Talk):
            with self.lock:
                answered = self._oracle.last is not None
                self.view.dialog.append((output.text, observation["oracle_answer"], answered))
                self.view.status = Status.PLAYING
        self._publish(observation, int(info["steps"]))
        return observation, terminated or truncated

    def _publish(self, observation: Observation, steps: int) -> None:
        sim = self._require_env().sim
        state = sim.state
        x, y, z = state.position
        storey = None if sim.storeys is None else sim.storeys.level_of(y)
        with self.lock:
            view = self.view
            view.rgb = observation["rgb"]
            view.frame_number += 1
            view.steps = steps
            view.questions_left = int(observation["questions_left"])
            view.pose = (x, z, state.yaw)
            view.storey = storey
            if not view.trail or view.trail[-1] != (x, z):
                view.trail.append((x, z))
                view.trail_storeys.append(storey)
        self.signal.bump()

    def _set_status(self, status: str) -> None:
        with self.lock:
            self.view.status = status
        self.signal.bump()

    def _abandon(self, why: str) -> None:
        self._end(
            self._require_env().record(self.label, error=f"abandoned: {why}"), Status.ABANDONED
        )

    def _end(self, record: EpisodeRecord, status: str) -> None:
        from vlln.tasks.metrics import success

        record = replace(record, oracle=self.oracle_kind.value)
        self._finish(self, record)
        self._journal.end(status)
        with self.lock:
            self.view.status = status
            self.view.success = success(record)
            self.view.end_reason = record.end_reason
            self.view.error = record.error
        self.signal.bump()

    def _require_env(self) -> NavigationEnv:
        if self._env is None:
            raise RuntimeError("the session's environment is not built yet")
        return self._env

    def _seed(self, role: str) -> int:
        spec = self.spec
        return derive_seed(spec.seed, role, spec.scene_id, spec.episode_id)


def _output_of(step: Step) -> object:
    if step.action is not None:
        return Action[step.action]
    if step.question is not None:
        return Talk(step.question)
    return step.invalid


def _describe(error: Exception) -> str:
    return f"{type(error).__name__}: {error}"[:2000]
