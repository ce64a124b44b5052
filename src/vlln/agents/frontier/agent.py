"""The frontier-exploration baseline with a simulated detector and an optional dialog.

It follows the reference's data-collection policy (docs/reference-facts.md §5): a 360° scan, then
frontier exploration on a map built from depth, and once an instance of the target category
that fits what is known about the target is seen, a walk up to it and STOP facing it. It never
reads the expert action or the geodesic field; it sees objects through a detector simulated on
the instance-id image: the ground-truth one (``truth``, privileged: every instance in view,
exactly labelled) or a noisy one (``noisy``: misses, look-alike categories, misread attributes;
:mod:`vlln.agents.frontier.perception`).

What is known about the target comes from the instruction's adjectives (IGN) and, with a
question budget (IIGN, or IGN when given one), from the oracle: a colour question at the start
unless the instruction named the colour, "is this the one?" before stopping at a candidate,
and "which way?" when exploration drags on or gets stuck. Those are the default of a pluggable
dialog policy (:mod:`.asking`); a learned one decides instead with ``dialog_policy``. Every
random choice comes from generators seeded by the agent's seed and the episode id.

In a house with several storeys it keeps a map per storey (:mod:`.storeys`), sees the stairs
through its detector, takes them once its storey is explored or when the oracle says the
target is upstairs or downstairs (:mod:`.crossing`), and goes only to candidates on the
storey it is on.
"""

from __future__ import annotations

import math
import zlib

import numpy as np

from vlln.agents.frontier import dialog, which_one
from vlln.agents.frontier.asking import Belief, Decision, DialogPolicy, FixedTriggers, Point
from vlln.agents.frontier.config import FrontierConfig
from vlln.agents.frontier.crossing import Crossing
from vlln.agents.frontier.detector import Candidate, CandidateTracker
from vlln.agents.frontier.explorer import Explorer
from vlln.agents.frontier.mapping import ObstacleMap, Pose
from vlln.agents.frontier.perception import check_detector, make_detector
from vlln.agents.frontier.planner import turn_toward
from vlln.agents.frontier.progress import Trail
from vlln.agents.frontier.stairs import StairsSight
from vlln.agents.frontier.storeys import Storey, StoreyMemory
from vlln.errors import ConfigError
from vlln.sim.agent import Action
from vlln.tasks.env import EpisodeInfo, Observation
from vlln.tasks.record import StopReason
from vlln.tasks.spec import AgentOutput, Talk, TaskType
from vlln.world.frame import wrap_angle, yaw_of

_COUNTED = (Action.STOP, Action.MOVE_FORWARD, Action.TURN_LEFT, Action.TURN_RIGHT)


class FrontierAgent:
    """Frontier exploration + detection (+ questions when the task gives a budget)."""

    name = "frontier"
    privileged = True  # the detectors are simulated on the instance-id image
    snapshottable = True  # deep copies are faithful; the budget is read only from refusals

    def __init__(
        self,
        seed: int = 0,
        config: FrontierConfig | None = None,
        detector: str = "truth",
        dialog_policy: DialogPolicy | None = None,
    ) -> None:
        self.seed = int(seed)
        self.config = config or FrontierConfig()
        self.dialog_policy = dialog_policy or FixedTriggers(self.config.route_after)
        if not self.config.asks:
            self.name = "fbe"
        elif self.config.compares:
            self.name = "frontier-compare"
        self.detector = check_detector(detector)
        self._info: EpisodeInfo | None = None
        self._stop_reason: StopReason | None = None

    # ----------------------------------------------------------------- episode start
    def reset(self, episode: EpisodeInfo) -> None:
        if episode.detector is None:
            raise ConfigError(
                "the frontier agent is privileged: run it in NavigationEnv(privileged=True) so "
                "that EpisodeInfo carries the detector lookup"
            )
        cfg = self.config
        self._info = episode
        episode_key = zlib.crc32(episode.episode_id.encode())
        self._rng = np.random.default_rng([self.seed, episode_key])
        detector = make_detector(self.detector, episode.detector, [self.seed, episode_key])
        self._turn = math.radians(episode.motion.turn_deg)
        self._tilt_step = math.radians(episode.motion.tilt_step_deg)
        self._stairs = StairsSight(detector)
        self.memory = StoreyMemory(self._new_storey)
        self.crossing = Crossing(self.memory, self._turn)
        self.tracker = CandidateTracker(
            episode.camera,
            detector,
            episode.object_category,
            self.map,
            min_pixels=cfg.min_detection_pixels,
        )
        vocabulary = dialog.Vocabulary.from_attributes(
            d.attributes for d in detector.labels.values()
        )
        self._answer_vocabulary = vocabulary.restricted(dialog.ANSWER_ATTRIBUTES)
        self.known: dict[str, str] = {}
        if episode.task == TaskType.IGN:
            self.known = dialog.stated_attributes(
                episode.instruction, episode.object_category, vocabulary
            )
        self.rejected: set[int] = set()
        self.confirmed: int | None = None
        self._compared: set[frozenset[int]] = set()  # candidates in view asked about together
        self._target: int | None = None
        self._pending: tuple[str, int | None] | None = None
        self._asked_attribute = "color" in self.known  # IGN: the instruction may name it
        self._opened = False  # whether the policy was consulted at the start
        self._verdicts: dict[int, str | None] = {}  # the policy's choice at each candidate
        self._dialog_closed = False
        self._questions_left = cfg.question_budget
        self._aim: int | None = None
        self._looks = 0
        self._exhausted = False  # no frontier left: any candidate of the category will do
        self._aim_failed_at: tuple[float, float] | None = None
        self._scan_left = cfg.scan_turns
        self._explore_steps = 0
        self._hint: tuple[float, int] | None = None  # (yaw, last step it applies)
        self._steps = 0
        self._height = 0.0  # feet above the start's
        self._last: tuple[AgentOutput, Pose] | None = None
        self._trail = Trail(cfg.stuck_steps, cfg.stuck_distance)
        self._started = False
        self._stop_reason = None

    def _new_storey(self, floor: float) -> Storey:
        obstacle_map = ObstacleMap(self.episode.camera, self.config.map)
        explorer = Explorer(obstacle_map, self._turn, self._rng, self.config.explorer)
        explorer.look_down = self._stairs.possible
        return Storey(floor, obstacle_map, explorer)

    @property
    def map(self) -> ObstacleMap:
        """The map of the storey the agent is on."""
        return self.memory.here.map

    @property
    def explorer(self) -> Explorer:
        return self.memory.here.explorer

    @property
    def episode(self) -> EpisodeInfo:
        if self._info is None:
            raise ConfigError("call reset(episode_info) before act()")
        return self._info

    # ----------------------------------------------------------------- one step
    def act(self, observation: Observation) -> AgentOutput:
        self.episode  # noqa: B018  (raises before reset)
        gps = observation["gps"]
        pose = Pose(float(gps[0]), float(gps[1]), float(observation["compass"]))
        tilt = float(observation["tilt"])
        self._height = float(observation.get("height", 0.0))
        if self._pending is not None:
            kind, about = self._pending
            self._pending = None
            self._read_answer(kind, about, str(observation["oracle_answer"] or ""), pose)
        else:
            self._sense(observation, pose, tilt)
        action = self._decide(pose, tilt)
        self._last = (action, pose)
        if action in (Action.LOOK_UP, Action.LOOK_DOWN):
            self._looks += 1
        if isinstance(action, Action) and action in _COUNTED:
            self._steps += 1
            self._trail.add(pose.x, pose.z, action == Action.MOVE_FORWARD)
        return action

    def _sense(self, observation: Observation, pose: Pose, tilt: float) -> None:
        known = len(self.memory.storeys)
        if self.memory.observe(pose.x, pose.z, self._height) and not self.crossing.busy:
            self._arrived(pose, new=len(self.memory.storeys) > known)
        if not self._started:
            self.map.mark_free_disc(pose, 0.3)
            self._started = True
        if self._last is not None:
            action, before = self._last
            moved = math.hypot(pose.x - before.x, pose.z - before.z)
            if action == Action.MOVE_FORWARD and moved < 0.05:
                self.map.mark_blocked_ahead(before, 0.3, 0.1)
                self.explorer.drop_path()
                self.crossing.bumped(pose)
        depth = observation["depth"]
        feet = self._height - self.memory.here.floor
        walkable = self._stairs.pixels(self.map, observation["instance_ids"], depth)
        if tilt == 0.0:
            new = self.map.update(depth, pose, 0.0, feet, walkable)
            self.explorer.note_obstacles(new)
        elif walkable is not None:
            self.map.update_stairs(depth, pose, tilt, feet, walkable)
        self.tracker.update(observation["instance_ids"], depth, pose, tilt, self._height)

    def _arrived(self, pose: Pose, new: bool) -> None:
        """On another storey: plans and hints made on the last one no longer apply."""
        for storey in self.memory.storeys:
            storey.explorer.drop_path()
        self._hint = None
        self._trail.clear()
        self._explore_steps = 0
        if self.memory.on_floor(self._height):
            self.map.mark_free_disc(pose, 0.3)
        if new:
            self._scan_left = self.config.scan_turns

    def _decide(self, pose: Pose, tilt: float) -> AgentOutput:
        if self._can_ask() and not self._opened:
            self._opened = True
            kind = self._consult(Point.START, pose, False)
            if kind is not None:
                return self._question(kind)
        if tilt != 0.0 and self._aim is None:
            return self._level(tilt)
        if self._scan_left > 0:
            self._scan_left -= 1
            self._trail.clear()
            return Action.TURN_LEFT
        stuck = self._trail.stuck()
        if self.crossing.busy:
            climb = self.crossing.step(pose, self._height, stuck)
            if climb is not None:
                return climb
            if self.crossing.walk_ended:
                self.crossing.walk_ended = False
                self._arrived(pose, new=self.crossing.arrived_new)
            stuck = False
        if stuck:
            self.explorer.give_up_goal()
        candidate = self._choose_candidate(pose)
        if candidate is not None:
            action = self._pursue(candidate, pose, tilt)
            if action is not None:
                self._explore_steps = 0
                return action
        self._aim = None
        if tilt != 0.0:
            return self._level(tilt)
        every = self.dialog_policy.explore_every
        if self._can_ask(spare=True) and (stuck or self._explore_steps >= every):
            self._explore_steps = 0
            kind = self._consult(Point.EXPLORE, pose, stuck)
            if kind is not None:
                return self._question(kind)
        self._explore_steps += 1
        hint = self._hint[0] if self._hint and self._hint[1] >= self._steps else None
        move = self.crossing.toward_hint(pose, self._height)
        if move is None:
            move = self.explorer.step(pose, hint)
        if move is not None:
            return move
        self.memory.here.exhausted = True
        action = self.crossing.leave(pose, self._height)
        if action is not None:
            return action
        if not self._exhausted:
            self._exhausted = True
            fallback = self._choose_candidate(pose)
            if fallback is not None:
                action = self._pursue(fallback, pose, tilt)
                if action is not None:
                    return action
        return self._stop(StopReason.EXPLORED)

    def _stop(self, reason: StopReason) -> Action:
        self._stop_reason = reason
        return Action.STOP

    def stop_reason(self) -> StopReason | None:
        """Why it stopped: at a candidate, or with nothing left to explore (the taxonomy's
        exploration failure)."""
        return self._stop_reason

    # ----------------------------------------------------------------- candidates
    def _choose_candidate(self, pose: Pose) -> Candidate | None:
        """The candidate to go to: the confirmed one, else the current one while it still fits,
        else the nearest that fits what is known (anything not rejected once the house is
        explored or the steps run out)."""
        detected = {c.instance_id: c for c in self.tracker.detected()}
        if self.confirmed is not None and self.confirmed in detected:
            return detected[self.confirmed]
        pool = [
            c
            for c in detected.values()
            if self._on_this_storey(c)
            and c.instance_id not in self.rejected
            and c.instance_id not in self.explorer.unreachable
            and (self._settling() or dialog.matches_known(c.attributes, self.known))
        ]
        if not pool:
            self._target = None
            return None
        current = next((c for c in pool if c.instance_id == self._target), None)
        if current is None:
            current = min(pool, key=lambda c: (c.distance_from(pose.x, pose.z), c.instance_id))
            self._target = current.instance_id
        return current

    def _settling(self) -> bool:
        """Whether any unrejected instance of the category will do: the house is explored,
        or the steps are running out (:attr:`FrontierConfig.settle_after`)."""
        return self._exhausted or self._steps >= self.config.settle_after

    def _on_this_storey(self, candidate: Candidate) -> bool:
        """Whether the candidate stands on the agent's storey, where the target may be."""
        storey = self.memory.storey_of(candidate.lowest)
        if storey != self.memory.current:
            return False
        return self.crossing.fits_hint(storey)

    def _pursue(self, candidate: Candidate, pose: Pose, tilt: float) -> AgentOutput | None:
        """Walk to the candidate, ask about it on the way if the dialog allows, then stop."""
        cfg = self.config
        near = candidate.distance_from(pose.x, pose.z)
        cx, _, cz = candidate.centroid
        if self._needs_confirmation(candidate) and self._may_aim(pose) and near <= cfg.ask_distance:
            kind = self._verdict(candidate, pose)
            if kind == "disambiguation":
                action = self._aim_and_ask(candidate, pose, tilt)
                if action is not None:
                    return action
            elif kind is not None:
                return self._question(kind)
        self._aim = None
        if tilt != 0.0:
            return self._level(tilt)
        if near > cfg.arrive_distance and candidate.instance_id not in self.explorer.unreachable:
            action = self.explorer.approach(candidate, pose)
            if action is not None:
                return action
            if candidate.instance_id in self.explorer.unreachable:
                if candidate.instance_id != self.confirmed:
                    return None
                return self._stop(StopReason.CANDIDATE)
        # As close as it gets: face the object and stop.
        error = wrap_angle(yaw_of(cx - pose.x, cz - pose.z) - pose.yaw)
        return turn_toward(error, self._turn) or self._stop(StopReason.CANDIDATE)

    def _aim_and_ask(self, candidate: Candidate, pose: Pose, tilt: float) -> AgentOutput | None:
        """Face the candidate (turns, then camera tilt) and ask about it; None when it is not
        in the middle of the view once faced (occluded), so the agent walks on."""
        self._aim = candidate.instance_id
        cx, cy, cz = candidate.centroid
        error = wrap_angle(yaw_of(cx - pose.x, cz - pose.z) - pose.yaw)
        turn = turn_toward(error, self._turn)
        if turn is not None:
            return turn
        info = self.episode
        eye = self._height + info.camera.height_m
        elevation = math.atan2(cy - eye, math.hypot(cx - pose.x, cz - pose.z))
        low = math.radians(info.motion.min_tilt_deg)
        high = math.radians(info.motion.max_tilt_deg)
        want = min(max(round(elevation / self._tilt_step) * self._tilt_step, low), high)
        if tilt < want - 1e-6:
            return Action.LOOK_UP
        if tilt > want + 1e-6:
            return Action.LOOK_DOWN
        if self.tracker.centred(candidate.instance_id, self.config.min_central_pixels):
            return self._inspect(candidate)
        self._aim = None
        self._aim_failed_at = (pose.x, pose.z)
        return None

    def _inspect(self, candidate: Candidate) -> AgentOutput | None:
        """With the candidate in the middle of the view: ask "is this the one?", or, comparing
        with others of the category in view, which one it is (None: go on without asking)."""
        if self.config.compares:
            together = frozenset(instance for instance, _ in self._in_view())
            if len(together) >= 2 and together not in self._compared:
                self._compared.add(together)
                return self._ask("comparison", which_one.COMPARISON_QUESTION)
        return self._question("disambiguation", candidate.instance_id)

    def _in_view(self) -> list[tuple[int, float]]:
        """The candidates in view not yet ruled out, on this storey, as (id, column)."""
        seen = self.tracker.in_view(self.config.min_detection_pixels, self.rejected)
        return [s for s in seen if self._on_this_storey(self.tracker.candidates[s[0]])]

    def _may_aim(self, pose: Pose) -> bool:
        """After a failed aim, try again only from somewhere else."""
        failed = self._aim_failed_at
        if self._looks >= self.config.max_looks:
            return False
        return failed is None or math.hypot(pose.x - failed[0], pose.z - failed[1]) > 0.5

    def _needs_confirmation(self, candidate: Candidate) -> bool:
        return candidate.instance_id != self.confirmed and self._can_ask()

    # ----------------------------------------------------------------- dialog
    def _can_ask(self, spare: bool = False) -> bool:
        info = self._info
        if info is None or self._dialog_closed or not self.config.asks:
            return False
        reserve = self.config.reserve_questions if spare and self.confirmed is None else 0
        return self._questions_left > reserve

    def _consult(self, point: Point, pose: Pose, stuck: bool) -> str | None:
        """The dialog policy's choice at ``point``: a question kind to ask, or None."""
        allowed = [] if self._asked_attribute else ["attribute"]
        allowed.append("disambiguation" if point == Point.CANDIDATE else "route")
        return self.dialog_policy.choose(Decision(point, tuple(allowed), self._belief(pose, stuck)))

    def _verdict(self, candidate: Candidate, pose: Pose) -> str | None:
        """The policy's choice at a candidate within asking distance, asked once per
        candidate (again after a colour question it chose there)."""
        key = candidate.instance_id
        if key not in self._verdicts:
            kind = self._consult(Point.CANDIDATE, pose, False)
            if kind == "attribute":
                return kind
            self._verdicts[key] = kind
        return self._verdicts[key]

    def _belief(self, pose: Pose, stuck: bool) -> Belief:
        seen = self.tracker.detected()
        fitting = [
            c.distance_from(pose.x, pose.z)
            for c in seen
            if c.instance_id not in self.rejected
            and self._on_this_storey(c)
            and dialog.matches_known(c.attributes, self.known)
        ]
        cell = self.map.cell_size**2
        return Belief(
            budget_left=self._questions_left / max(self.config.question_budget, 1),
            steps=self._steps / max(self.episode.max_steps, 1),
            colour_known="color" in self.known,
            attribute_asked=self._asked_attribute,
            known_attributes=len(self.known),
            candidates_seen=len(seen),
            fitting_distance=min(fitting) if fitting else None,
            rejected=len(self.rejected),
            confirmed=self.confirmed is not None,
            explore_steps=self._explore_steps,
            explored_m2=sum(float(s.map.explored.sum()) * cell for s in self.memory.storeys),
            stuck=stuck,
            storeys=len(self.memory.storeys),
            hinted=self._hint is not None and self._hint[1] >= self._steps,
        )

    def _question(self, kind: str, about: int | None = None) -> Talk:
        """Ask a question of ``kind`` in one of its phrasings."""
        if kind == "attribute":
            self._asked_attribute = True
        text = dialog.question(dialog.TEMPLATES[kind], self.episode.object_category, self._rng)
        return self._ask(kind, text, about)

    def _ask(self, kind: str, text: str, about: int | None = None) -> Talk:
        self._pending = (kind, about)
        return Talk(text)

    def _read_answer(self, kind: str, about: int | None, answer: str, pose: Pose) -> None:
        self._aim = None
        self._trail.clear()  # a question is a fresh start for the stuck test
        if dialog.is_refusal(answer):
            self._dialog_closed = True
            return
        self._questions_left -= 1
        if kind == "attribute":
            self.known.update(self._answer_vocabulary.parse(answer))
        elif kind == "disambiguation" and about is not None:
            verdict = dialog.parse_yes_no(answer)
            if verdict or dialog.says_too_far(answer):
                self.confirmed = about
            elif verdict is False:
                self.rejected.add(about)
                self.known.update(self._answer_vocabulary.parse(answer))
            if self.config.compares:
                self._take_pick(which_one.read_clarification(answer))
        elif kind == "comparison":
            self._take_pick(which_one.read_comparison(answer))
        elif kind == "route":
            storey = dialog.parse_storey(answer)
            if storey is not None or dialog.parse_route(answer) is not None:
                self.crossing.note_hint(storey or 0)
            if dialog.says_arrived(answer):
                self._scan_left = self.config.scan_turns
                return
            turn = dialog.parse_route(answer)
            if turn is not None:
                self._hint = (wrap_angle(pose.yaw + turn), self._steps + self.config.hint_steps)
                self.explorer.drop_path()

    def _take_pick(self, pick: which_one.Pick | None) -> None:
        """An answer naming the target among the candidates in view confirms it."""
        if pick is not None:
            chosen = which_one.take(pick, self._in_view(), self.rejected)
            if chosen is not None:
                self.confirmed = self._target = chosen

    # ----------------------------------------------------------------- helpers
    def _level(self, tilt: float) -> Action:
        return Action.LOOK_UP if tilt < 0.0 else Action.LOOK_DOWN
