"""The navigation environment, one class for the three tasks.

Datasheet
---------
* **Tasks**: IIGN (instruction "Search for the <category>.", dialog with an oracle), IGN (a full
  description that singles out the instance; dialog when given a budget, as the paper runs
  its agents), ObjectNav (any instance of the category is a goal, no dialog).
* **Actions**: :class:`vlln.sim.agent.Action` (STOP, MOVE_FORWARD 0.25 m, TURN_LEFT/RIGHT 30°,
  LOOK_UP/DOWN 30°), :class:`vlln.tasks.spec.Talk` (a question) or
  :class:`vlln.tasks.spec.PixelGoal` (a pixel of the current frame, normally the look-down one,
  to walk to: back-projected with depth and tilt, snapped to the navigable area; the camera
  returns level; counted like a LOOK unless the camera was tilted, whose LOOK_DOWN counted).
  :class:`vlln.tasks.spec.FailedOutput` (a model's output that could not be read, or a server
  that gave none), a pixel that shows no reachable floor (or floor the agent stands on or
  cannot step toward), and anything else are failed actions: recorded by kind, the agent does
  not move, the camera returns level, and it counts as a step.
* **Observations** (a dict): ``rgb`` (H, W, 3) uint8; ``depth`` (H, W) float32 metres;
  ``gps`` float32 (x, z) in metres from the start in the start's frame (the start heading looks
  along -z); ``height`` the feet's height above the start's (metres; it changes only on
  stairs); ``compass`` yaw relative to the start heading (radians, left positive); ``tilt``
  (radians, up positive); ``instruction``; ``oracle_answer`` (the answer to a TALK on the step
  right after it, else None); ``questions_left``; ``waypoint_action`` (after a pixel goal: the
  next action of a shortest-path follower, radius 0.25 m, toward its floor point; None when
  there is no goal, it is reached, or the agent did something else). Privileged agents also
  get ``instance_ids`` (H, W) int32 and ``expert_action`` (the shortest-path follower's next
  action), and their :class:`EpisodeInfo` carries ``detector``: a ground-truth detector's
  lookup from instance id to category and attributes (what a perfect object detector with
  attribute recognition would report), as the reference's data collection uses.
* **Termination**: STOP ends the episode (``terminated``). ``truncated`` at 500 counted steps
  (STOP, FORWARD, TURN and failed actions count; LOOK and TALK do not) or when the LOOK, TALK
  or failed-action caps are reached.
* **Dialog**: the first ``dialog_budget`` questions are answered; later ones get
  :data:`vlln.tasks.spec.REFUSAL_MESSAGE`. Questions are answered on IIGN (default budget 5)
  and IGN (default budget 0), never on ObjectNav.
* **Refusal**: an episode whose start is on no storey of the scene or not navigable, or whose
  goals cannot be reached from it on their own storeys, is refused at ``reset``
  (:mod:`vlln.tasks.refusal`), never played on another storey.
* **Reward**: the decrease of geodesic distance to the nearest goal view point, plus 2.5 on
  success; the benchmark scores records, not rewards.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from vlln.errors import ConfigError, EpisodeRefusedError
from vlln.sim.agent import Action, AgentState, MotionConfig
from vlln.sim.camera import CameraSpec
from vlln.sim.follower import GreedyFollower
from vlln.sim.simulator import Simulator
from vlln.tasks.episode import Episode
from vlln.tasks.goals import goal_instances, goal_points
from vlln.tasks.oracle_protocol import EpisodeContext, Oracle, Question
from vlln.tasks.record import DialogTurn, EndReason, EpisodeRecord, ModelCall, StopReason
from vlln.tasks.refusal import reach_problem, start_problem
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import (
    REFUSAL_MESSAGE,
    AgentOutput,
    FailedOutput,
    PixelGoal,
    Talk,
    TaskConfig,
    TaskType,
)
from vlln.tasks.stop import distractor_distance, stop_instance
from vlln.tasks.taxonomy import target_observed
from vlln.tasks.waypoint import Waypoint, waypoint_for_pixel
from vlln.world.frame import quaternion_to_yaw, wrap_angle
from vlln.world.model import Attributes, Box3

Observation = dict[str, Any]
SUCCESS_REWARD = 2.5


@dataclass(frozen=True)
class EpisodeInfo:
    """What an agent is told when an episode starts."""

    episode_id: str
    task: TaskType
    instruction: str
    object_category: str
    camera: CameraSpec
    motion: MotionConfig
    dialog_budget: int
    max_steps: int
    detector: dict[int, DetectedObject] | None = None  # privileged agents only


@dataclass(frozen=True)
class DetectedObject:
    """What the ground-truth detector reports for one instance id."""

    category: str
    attributes: Attributes


class NavigationEnv:
    """Plays episodes of one task; Gymnasium's ``reset``/``step`` conventions."""

    def __init__(
        self,
        episodes: list[Episode],
        config: TaskConfig,
        scenes: SceneCache | None = None,
        oracle: Oracle | None = None,
        privileged: bool = False,
    ) -> None:
        if config.dialog_enabled and oracle is None:
            raise ConfigError(
                f"{config.task.value} with a dialog budget needs an oracle; pass oracle="
            )
        self.episodes = episodes
        self.config = config
        self.scenes = scenes or SceneCache()
        self.oracle = oracle
        self.privileged = privileged
        self._episode: Episode | None = None

    # ----------------------------------------------------------------- episode start
    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[Observation, dict[str, Any]]:
        """Start an episode: ``options={"episode_index": i}`` (default: drawn with ``seed``).
        An episode whose start or goals are not reachable on their own storeys raises
        :class:`~vlln.errors.EpisodeRefusedError` (:mod:`vlln.tasks.refusal`)."""
        options = options or {}
        if "episode_index" in options:
            index = int(options["episode_index"])
        else:
            index = int(np.random.default_rng(seed).integers(len(self.episodes)))
        if not 0 <= index < len(self.episodes):
            raise ConfigError(f"episode_index {index} is outside 0..{len(self.episodes) - 1}")
        episode = self.episodes[index]
        self._episode = episode
        self.sim: Simulator = self.scenes.get(episode.scene_id)
        house = self.sim.house
        self.targets = goal_instances(self.sim.house, episode, self.config.task)
        x0, y0, z0 = episode.start_position
        problem = start_problem(self.sim, x0, y0, z0)
        if problem is not None:
            raise EpisodeRefusedError(episode.episode_id, episode.scene_id, problem)
        self.goal_points = goal_points(self.sim, episode, self.targets)
        self.field = self.sim.distance_field(self.goal_points)
        problem = reach_problem(self.sim, self.field, (x0, y0, z0), self.goal_points)
        if problem is not None:
            raise EpisodeRefusedError(episode.episode_id, episode.scene_id, problem)
        self.follower = GreedyFollower(
            self.sim.nav, self.field, self.config.success_radius, self.sim.config.motion
        )
        start = AgentState(
            (x0, y0, z0),
            quaternion_to_yaw(episode.start_rotation),
            0.0,
        )
        self._start = start
        self._steps = self._looks = self._talks = self._failed = 0
        self._questions_answered = 0
        self._path_length = 0.0
        self._trace: list[float] = []
        self._positions: list[list[float]] = [[start.position[0], start.position[2], start.yaw]]
        self._heights: list[float] = [y0] if self.sim.storeys is not None else []
        self._actions: list[str] = []
        self._dialog: list[DialogTurn] = []
        self._seen_step: int | None = None
        self._end: EndReason | None = None
        self._answer: str | None = None
        self._failures: dict[str, int] = {}
        self._waypoint: Waypoint | None = None
        self._waypoint_action: Action | None = None
        self._distance = self.field.distance(start.position[0], start.position[2], y0)
        self._d0 = self._distance
        if self.oracle is not None and self.config.dialog_enabled:
            self.oracle.start(EpisodeContext(self.sim, self.targets[0], tuple(self.goal_points)))
        observation = self.sim.reset(start)
        self._frame = observation.frame
        self._note_target_seen()
        return self._observe(), {"episode_id": episode.episode_id, "house": house.name}

    @property
    def questions_answered(self) -> int:
        """Questions the oracle has answered in this episode (refusals not counted)."""
        return self._questions_answered

    def episode_info(self) -> EpisodeInfo:
        episode = self._require_episode()
        return EpisodeInfo(
            episode.episode_id,
            self.config.task,
            episode.instruction.instruction_text,
            episode.object_category,
            self.sim.config.camera,
            self.sim.config.motion,
            self.config.dialog_budget if self.config.dialog_enabled else 0,
            self.config.max_steps,
            self._detector() if self.privileged else None,
        )

    def _detector(self) -> dict[int, DetectedObject]:
        return {
            inst.id: DetectedObject(inst.category, inst.attributes)
            for inst in self.sim.house.instances
        }

    # ----------------------------------------------------------------- stepping
    def step(self, action: AgentOutput) -> tuple[Observation, float, bool, bool, dict[str, Any]]:
        episode = self._require_episode()
        if self._end is not None:
            raise ConfigError(f"episode {episode.episode_id} has ended; call reset() first")
        self._answer = None
        collided = False
        before = self._distance
        if self._waypoint_action is None or action != self._waypoint_action:
            self._waypoint = None  # the agent left the walk to its pixel goal
        if isinstance(action, Talk):
            self._talk(action.text)
        elif isinstance(action, Action):
            collided = self._act(action)
        elif isinstance(action, PixelGoal):
            self._pixel_goal(action)
        elif isinstance(action, FailedOutput):
            self._fail(f"FAILED:{action.kind}", action.kind)
        else:
            self._fail(f"INVALID:{str(action)[:80]}", "invalid")
        self._check_caps()
        reward = before - self._distance
        if self._end == EndReason.STOP and self._distance < self.config.success_radius:
            reward += SUCCESS_REWARD
        terminated = self._end == EndReason.STOP
        truncated = self._end is not None and not terminated
        info = {"collided": collided, "steps": self._steps, "distance": self._distance}
        return self._observe(), reward, terminated, truncated, info

    def _act(self, action: Action) -> bool:
        self._actions.append(action.name)
        if action == Action.STOP:
            self._steps += 1
            self._trace.append(self._distance)
            self._end = EndReason.STOP
            return False
        before = self.sim.state.position
        observation = self.sim.step(action)
        self._frame = observation.frame
        after = observation.state.position
        if action in (Action.LOOK_UP, Action.LOOK_DOWN):
            self._looks += 1
        else:
            self._steps += 1
            dx, dy, dz = (a - b for a, b in zip(after, before, strict=True))
            self._path_length += math.hypot(dx, dz) if dy == 0.0 else math.hypot(dx, dy, dz)
            self._distance = self.field.distance(after[0], after[2], after[1])
            self._trace.append(self._distance)
            self._positions.append([after[0], after[2], observation.state.yaw])
            if self.sim.storeys is not None:
                self._heights.append(after[1])
        self._note_target_seen()
        return observation.collided

    def _fail(self, label: str, kind: str) -> None:
        """A wasted step; the camera returns level (e.g. after ``<move>↓`` and a bad reply)."""
        self._failed += 1
        self._failures[kind] = self._failures.get(kind, 0) + 1
        self._steps += 1
        self._actions.append(label)
        self._trace.append(self._distance)
        self._level_camera()

    def _pixel_goal(self, goal: PixelGoal) -> None:
        found = waypoint_for_pixel(self.sim, self._frame, goal.col, goal.row, self.sim.state)
        if isinstance(found, str):
            self._fail(f"FAILED:goal:{goal.col},{goal.row}", "goal")
            return
        if self.sim.state.tilt == 0.0:
            self._looks += 1  # on a tilted frame the LOOK_DOWN before it was counted
        self._actions.append(f"PIXEL:{goal.col},{goal.row}")
        self._waypoint = found
        self._level_camera()

    def _level_camera(self) -> None:
        state = self.sim.state
        if state.tilt != 0.0:
            self._frame = self.sim.reset(AgentState(state.position, state.yaw, 0.0)).frame
            self._note_target_seen()

    def _talk(self, text: str) -> None:
        self._talks += 1
        self._actions.append("TALK")
        budget = self.config.dialog_budget if self.config.dialog_enabled else 0
        if self._questions_answered >= budget or self.oracle is None:
            turn = DialogTurn(self._steps, text, REFUSAL_MESSAGE, "refused", False, backend="none")
        else:
            reply = self.oracle.answer(Question(text, self.sim.state, self._frame, self._walked()))
            turn = DialogTurn(
                self._steps,
                text,
                reply.answer,
                reply.question_type.value,
                True,
                backend=reply.backend,
                latency_ms=reply.latency_ms,
                prompt_tokens=reply.prompt_tokens,
                completion_tokens=reply.completion_tokens,
                fallback=reply.fallback,
                type_refused=reply.type_refused,
                help_kind=reply.help_kind,
            )
            self._questions_answered += 1
        self._answer = turn.answer
        self._dialog.append(turn)

    def _walked(self) -> tuple[tuple[float, float, float], ...]:
        """The positions (x, y, z) of the episode so far, the current one last."""
        heights = self._heights or [self.sim.state.position[1]] * len(self._positions)
        return tuple((p[0], y, p[1]) for p, y in zip(self._positions, heights, strict=True))

    def _check_caps(self) -> None:
        if self._end is not None:
            return
        cfg = self.config
        if self._failed >= cfg.max_failed_actions:
            self._end = EndReason.ERROR
        elif self._steps >= cfg.max_steps:
            self._end = EndReason.STEP_CAP
        elif self._looks >= cfg.max_look_actions:
            self._end = EndReason.LOOK_CAP
        elif self._talks >= cfg.max_talk_actions:
            self._end = EndReason.TALK_CAP

    def _error_text(self) -> str:
        """Why an episode ended in error when the agent gave no reason: the failed-action cap
        (with the failures by kind), or a record taken before the episode ended."""
        if self._failed >= self.config.max_failed_actions:
            kinds = ", ".join(f"{kind} {count}" for kind, count in sorted(self._failures.items()))
            return f"{self._failed} failed actions ({kinds}), the cap max_failed_actions"
        return "recorded before the episode ended"

    # ----------------------------------------------------------------- what the agent sees
    def _observe(self) -> Observation:
        state = self.sim.state
        start = self._start
        dx = state.position[0] - start.position[0]
        dz = state.position[2] - start.position[2]
        c, s = math.cos(start.yaw), math.sin(start.yaw)
        budget = self.config.dialog_budget if self.config.dialog_enabled else 0
        obs: Observation = {
            "rgb": self._frame.rgb,
            "depth": self._frame.depth,
            "gps": np.array([c * dx - s * dz, s * dx + c * dz], np.float32),
            "height": state.position[1] - start.position[1],
            "compass": wrap_angle(state.yaw - start.yaw),
            "tilt": state.tilt,
            "instruction": self._require_episode().instruction.instruction_text,
            "oracle_answer": self._answer,
            "questions_left": max(0, budget - self._questions_answered),
            "waypoint_action": self._next_waypoint_action(state),
        }
        if self.privileged:
            obs["instance_ids"] = self._frame.instance_ids
            obs["expert_action"] = self.follower.next_action(state)
        return obs

    def _next_waypoint_action(self, state: AgentState) -> Action | None:
        action = self._waypoint.next_action(state) if self._waypoint is not None else None
        if action is None:
            self._waypoint = None
        self._waypoint_action = action
        return action

    def _note_target_seen(self) -> None:
        if self._seen_step is not None:
            return
        ids = self._frame.instance_ids
        spec = self.sim.config.camera
        eye = spec.eye(self.sim.state.position)
        for target in self.targets:
            pixels = int(np.count_nonzero(ids == target.id))
            if pixels and target_observed(
                pixels, _box_distance(target.box, eye), spec.width, spec.height
            ):
                self._seen_step = self._steps
                return

    # ----------------------------------------------------------------- the record
    def record(
        self,
        agent_name: str,
        error: str | None = None,
        model_calls: Sequence[ModelCall] = (),
        stop_reason: StopReason | None = None,
    ) -> EpisodeRecord:
        """The finished episode as a record; an unfinished one is recorded as an error.
        ``model_calls`` are a model agent's calls, kept in the record as they were;
        ``stop_reason`` why the agent stopped, kept when the episode ended with STOP. A stop
        records what it was at (:mod:`vlln.tasks.stop`)."""
        episode = self._require_episode()
        end = self._end or EndReason.ERROR
        if end == EndReason.ERROR and error is None:
            error = self._error_text()
        stop_id = stop_category = near = None
        if end == EndReason.STOP:
            goals = {t.id for t in self.targets}
            level = self._frame.instance_ids if self.sim.state.tilt == 0.0 else None
            stop_id, stop_category = stop_instance(self.sim, level, goals, episode.object_category)
            near = distractor_distance(self.sim, goals, episode.object_category)
        return EpisodeRecord(
            episode_id=episode.episode_id,
            scene_id=episode.scene_id,
            task=self.config.task.value,
            agent=agent_name,
            budget=self.config.dialog_budget if self.config.dialog_enabled else 0,
            object_category=episode.object_category,
            target_ids=[t.id for t in self.targets],
            end_reason=end.value,
            steps=self._steps,
            geodesic_start=self._d0,
            geodesic_trace=list(self._trace),
            path_length=self._path_length,
            stop_instance_id=stop_id,
            stop_instance_category=stop_category,
            target_seen_step=self._seen_step,
            positions=[[round(v, 4) for v in p] for p in self._positions],
            heights=[round(y, 4) for y in self._heights],
            actions=list(self._actions),
            dialog=list(self._dialog),
            failed_actions=self._failed,
            error=error,
            failures=dict(self._failures),
            model_calls=list(model_calls),
            stop_reason=stop_reason.value if stop_reason and end == EndReason.STOP else None,
            distractor_distance=near,
        )

    def _require_episode(self) -> Episode:
        if self._episode is None:
            raise ConfigError("no episode is running; call reset() first")
        return self._episode

    def close(self) -> None:
        self.scenes.close()


def _box_distance(box: Box3, point: Any) -> float:
    """Straight-line distance from a point to the nearest point of a box."""
    gaps = [max(box.min[i] - point[i], 0.0, point[i] - box.max[i]) for i in range(3)]
    return math.sqrt(sum(g * g for g in gaps))
