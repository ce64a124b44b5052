"""The oracle behind the HTTP service: sessions over shared simulators, without any HTTP.

Clients send only a pose; the current view that the disambiguation rule needs is rendered here
from that pose, so a client in any language (or a robot whose camera differs from ours) gets the
same answer as an agent inside :class:`vlln.tasks.env.NavigationEnv`. A session answers with
the rule oracle or, created with ``"oracle": "helpful"``, the helpful oracle; the positions
walked that a question carries are the poses of the session's turns so far. The dialog
budget works as in the environment: the first ``dialog_budget`` questions are answered,
later ones get :data:`vlln.tasks.spec.REFUSAL_MESSAGE` (counted; the first few are kept in
the dialog).

Houses with several storeys work like one: goals and poses carry their height ``y`` (a
pose on the stairs stands at the tread's height), and route answers on or near a flight say
"go upstairs" or "downstairs".

Not thread-safe: the service calls it from one worker thread, which also keeps every OpenGL
context on one thread.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from vlln import __version__
from vlln.errors import VllnError
from vlln.oracle.helpful.oracle import reads_view as helpful_reads_view
from vlln.oracle.rule_oracle import reads_view
from vlln.oracle.settings import OracleBackend, OracleSettings
from vlln.oracle_service.config import ServiceConfig
from vlln.oracle_service.limits import BuildLimiter
from vlln.oracle_service.schemas import (
    AskRequest,
    AskResponse,
    CreateSessionRequest,
    CreateSessionResponse,
    DialogTurnView,
    HealthResponse,
    Pose,
    SessionView,
)
from vlln.oracle_service.schemas import QuestionType as WireQuestionType
from vlln.oracle_service.sessions import REFUSED_TURNS_KEPT, ServiceError, Session, SessionStore
from vlln.sim.agent import AgentState
from vlln.sim.renderer import Frame
from vlln.sim.simulator import Simulator
from vlln.sim.storeys import Storeys
from vlln.sim.viewpoints import GoalPoint
from vlln.tasks.episode import Episode
from vlln.tasks.oracle_protocol import EpisodeContext, Oracle, Question, QuestionType
from vlln.tasks.scenes import SceneCache, canonical_seed, procedural_scene_id
from vlln.tasks.spec import REFUSAL_MESSAGE
from vlln.world.frame import wrap_angle
from vlln.world.model import ObjectInstance

LOCAL = "local"  # the client of calls made in-process
_WIRE_TYPES: dict[QuestionType, WireQuestionType] = {
    QuestionType.ATTRIBUTE: "attribute",
    QuestionType.ROUTE: "route",
    QuestionType.DISAMBIGUATION: "disambiguation",
    QuestionType.OTHER: "other",
}
# The oracles a session may ask for: how to make one, and which questions make it look.
_ORACLES: dict[str, tuple[Callable[[int], Oracle], Callable[[str], bool]]] = {
    "rules": (OracleSettings(OracleBackend.RULES).make, reads_view),
    "helpful": (OracleSettings(OracleBackend.HELPFUL).make, helpful_reads_view),
}


class HostedOracle:
    """Creates, answers, shows and deletes dialog sessions."""

    def __init__(self, config: ServiceConfig) -> None:
        self.config = config
        self.scenes = SceneCache(config.simulator, capacity=config.scene_capacity)
        self.sessions = SessionStore(config.max_sessions)
        self.builds = BuildLimiter(config.client_builds_per_minute, config.builds_per_minute)
        self.episodes = {episode.episode_id: episode for episode in config.episodes}

    # ----------------------------------------------------------------- endpoints
    def create(self, request: CreateSessionRequest, client: str = LOCAL) -> CreateSessionResponse:
        """A new session; ``client`` (its address) is charged if its scene must be built."""
        if request.episode_id is not None:
            episode = self._episode(request.episode_id)
            scene_id, episode_id = episode.scene_id, episode.episode_id
            instruction: str | None = episode.instruction.instruction_text
            sim = self._simulator(scene_id, client)
            target, goals = self._episode_target(sim, episode)
        elif request.scene_id is not None and request.target_instance_id is not None:
            scene_id, episode_id, instruction = request.scene_id, None, None
            sim = self._simulator(scene_id, client)
            target = self._instance(sim, request.target_instance_id)
            goals = sim.view_points(target.box)
        else:
            raise ServiceError(
                422, "no target", "give scene_id and target_instance_id, or episode_id"
            )
        if not goals:
            raise ServiceError(
                422,
                "target has no view points",
                f"instance {target.id} ({target.category}) in {scene_id} has no navigable point "
                "within 0.6 m of its box, so it cannot be a navigation target; choose another",
            )
        session = Session(
            session_id=self.sessions.fresh_id(),
            scene_id=scene_id,
            episode_id=episode_id,
            target=target,
            goals=tuple(goals),
            instruction=instruction,
            dialog_budget=request.dialog_budget,
            oracle_name=request.oracle,
        )
        self._oracle(session, sim)
        self.sessions.add(session)
        return CreateSessionResponse(
            session_id=session.session_id,
            scene_id=scene_id,
            episode_id=episode_id,
            target_category=target.category,
            instruction=instruction,
            dialog_budget=session.dialog_budget,
            questions_left=session.questions_left,
        )

    def ask(self, session_id: str, request: AskRequest, client: str = LOCAL) -> AskResponse:
        session = self.sessions.get(session_id)
        sim = self._simulator(session.scene_id, client)
        state = self._state(sim, request.pose)
        kind: WireQuestionType
        help_kind: str | None = None
        if session.answered >= session.dialog_budget:
            answer, kind, answered = REFUSAL_MESSAGE, "refused", False
        else:
            oracle = self._oracle(session, sim)
            reply = oracle.answer(
                self._question(session, sim, request.question, state, session.dialog)
            )
            answer, kind, answered = reply.answer, _WIRE_TYPES[reply.question_type], True
            help_kind = reply.help_kind or None
            session.answered += 1
        turn = DialogTurnView(
            question=request.question,
            answer=answer,
            question_type=kind,
            answered=answered,
            pose=request.pose,
            help_kind=help_kind,
        )
        if answered or session.refused < REFUSED_TURNS_KEPT:
            session.dialog.append(turn)
        if not answered:
            session.refused += 1
        return AskResponse(
            answer=answer,
            question_type=turn.question_type,
            answered=answered,
            questions_left=session.questions_left,
            help_kind=help_kind,
        )

    def view(self, session_id: str) -> SessionView:
        session = self.sessions.get(session_id)
        return SessionView(
            session_id=session.session_id,
            scene_id=session.scene_id,
            episode_id=session.episode_id,
            target_category=session.target.category,
            dialog_budget=session.dialog_budget,
            questions_left=session.questions_left,
            refused_questions=session.refused,
            dialog=list(session.dialog),
        )

    def delete(self, session_id: str) -> None:
        self.sessions.remove(session_id)

    def health(self) -> HealthResponse:
        return HealthResponse(
            status="ok",
            version=__version__,
            sessions=len(self.sessions),
            max_sessions=self.sessions.capacity,
        )

    def close(self) -> None:
        self.scenes.close()

    # ----------------------------------------------------------------- look-ups
    def _oracle(self, session: Session, sim: Simulator) -> Oracle:
        """The session's oracle on ``sim``, started afresh (answered turns replayed, so the
        seeded wording goes on where it was) when the scene cache had dropped its house."""
        if session.oracle is not None and session.simulator is sim:
            return session.oracle
        make, _ = _ORACLES[session.oracle_name]
        oracle = make(self.config.oracle_seed)
        oracle.start(EpisodeContext(sim, session.target, session.goals))
        for index, turn in enumerate(session.dialog):
            if turn.answered:
                state = self._state(sim, turn.pose)
                earlier = session.dialog[:index]
                oracle.answer(self._question(session, sim, turn.question, state, earlier))
        session.oracle, session.simulator = oracle, sim
        return oracle

    def _question(
        self,
        session: Session,
        sim: Simulator,
        text: str,
        state: AgentState,
        earlier: list[DialogTurnView],
    ) -> Question:
        """The question as the session's oracle takes it: the view (rendered where its answer
        looks at it) and the positions walked, the earlier turns' poses and then ``state``."""
        _, reads = _ORACLES[session.oracle_name]
        walked = (*(self._state(sim, turn.pose).position for turn in earlier), state.position)
        return Question(text, state, _view(sim, state, reads(text)), walked)

    def _simulator(self, scene_id: str, client: str) -> Simulator:
        try:
            canonical_seed(scene_id)
        except VllnError as error:
            raise ServiceError(
                404,
                "unknown scene",
                f"{error}. Scene ids have the form vlln/house_<seed> with the seed in ASCII "
                f"digits, zero-padded to 5, e.g. {procedural_scene_id(76)!r}",
            ) from None
        if self.scenes.holds(scene_id):
            return self.scenes.get(scene_id)
        self.builds.admit(client)
        try:
            sim = self.scenes.get(scene_id)
        except VllnError as error:
            raise ServiceError(422, "scene cannot be built", str(error)) from None
        for session in self.sessions.sessions():  # drop oracles of houses the cache let go
            if session.simulator is not None and not self.scenes.holds_simulator(session.simulator):
                session.oracle = session.simulator = None
        return sim

    def _episode(self, episode_id: str) -> Episode:
        episode = self.episodes.get(episode_id)
        if episode is not None:
            return episode
        if not self.episodes:
            hint = "the server was started without an episode file; use scene_id instead"
        else:
            hint = f"{len(self.episodes)} episodes are loaded; check the id"
        raise ServiceError(404, "unknown episode", f"no episode {episode_id!r}: {hint}")

    def _instance(self, sim: Simulator, instance_id: int) -> ObjectInstance:
        instances = sim.house.instances
        for inst in instances:
            if inst.id == instance_id:
                return inst
        ids = sorted(inst.id for inst in instances)
        valid = f"ids {ids[0]}..{ids[-1]}" if ids else "no instances"
        raise ServiceError(
            404,
            "unknown target instance",
            f"{sim.house.name} has no instance {instance_id}; it has {valid}",
        )

    def _episode_target(
        self, sim: Simulator, episode: Episode
    ) -> tuple[ObjectInstance, list[GoalPoint]]:
        """The target and goal view points exactly as the navigation environment uses them."""
        raw = episode.instruction.instance_id[0] if episode.instruction.instance_id else ""
        try:
            instance_id = int(raw)
        except ValueError:
            raise ServiceError(
                422,
                "episode has no usable target",
                f"episode {episode.episode_id!r} names target instance {raw!r}, which is not a "
                "whole-number instance id of a vlln house",
            ) from None
        goals: list[GoalPoint] = [vp.position for g in episode.goals for vp in g.view_points]
        if sim.storeys is None:
            goals = [(point[0], point[-1]) for point in goals]
        return self._instance(sim, instance_id), goals

    def _state(self, sim: Simulator, pose: Pose) -> AgentState:
        """The pose as an agent state, if it stands on the navigable floor within limits."""
        x, y, z = pose.position
        if sim.storeys is not None:
            height = self._storey_height(sim.storeys, sim.house.name, x, y, z)
            return AgentState((x, height, z), wrap_angle(pose.yaw), self._tilt(sim, pose))
        grid = sim.grid
        on_floor = abs(y - grid.floor_y) <= self.config.floor_tolerance
        if not (on_floor and grid.is_navigable(x, z)):
            sx, sz = grid.snap_point(x, z)
            nearest = [round(sx, 4), grid.floor_y, round(sz, 4)]
            raise ServiceError(
                422,
                "pose off the navigable area",
                {
                    "message": (
                        f"position ({x:.3f}, {y:.3f}, {z:.3f}) is not on the navigable floor "
                        f"of {sim.house.name} (floor height {grid.floor_y:.3f} m, tolerance "
                        f"{self.config.floor_tolerance} m); the nearest navigable point is "
                        f"({nearest[0]:.3f}, {nearest[1]:.3f}, {nearest[2]:.3f})"
                    ),
                    "nearest_navigable_point": nearest,
                },
            )
        return AgentState((x, grid.floor_y, z), wrap_angle(pose.yaw), self._tilt(sim, pose))

    def _storey_height(self, storeys: Storeys, house: str, x: float, y: float, z: float) -> float:
        """The walking height under a pose in a house with several storeys (on the storey
        whose floor is nearest its y), if it stands there within the floor tolerance."""
        level = storeys.level_of(y)
        height = storeys.height_at(level, x, z)
        if abs(y - height) <= self.config.floor_tolerance and storeys.grids[level].is_navigable(
            x, z
        ):
            return height
        nearest = [round(v, 4) for v in storeys.snap_point(x, y, z)]
        raise ServiceError(
            422,
            "pose off the navigable area",
            {
                "message": (
                    f"position ({x:.3f}, {y:.3f}, {z:.3f}) is not on the navigable floor or "
                    f"stairs of storey {level} of {house} (walking height there {height:.3f} m, "
                    f"tolerance {self.config.floor_tolerance} m); the nearest navigable point "
                    f"is ({nearest[0]:.3f}, {nearest[1]:.3f}, {nearest[2]:.3f})"
                ),
                "nearest_navigable_point": nearest,
            },
        )

    @staticmethod
    def _tilt(sim: Simulator, pose: Pose) -> float:
        """The pose's tilt, if the camera can take it."""
        motion = sim.config.motion
        low, high = motion.min_tilt_deg, motion.max_tilt_deg
        tilt_deg = math.degrees(pose.tilt)
        if not low - 1e-6 <= tilt_deg <= high + 1e-6:
            raise ServiceError(
                422,
                "tilt out of range",
                f"tilt {pose.tilt:.4f} rad ({tilt_deg:.1f} deg) is outside the camera's range "
                f"{low:g}..{high:g} deg",
            )
        return pose.tilt


def _view(sim: Simulator, state: AgentState, looks: bool) -> Frame:
    """The view a question is asked from, as far as the oracle looks at it: only answers
    that read the view (``looks``, from the oracle's ``reads_view``) read it, and only its
    instance ids, so only those are rendered; the colour and depth images are read-only
    zeros of the right shape and every other question is answered without drawing anything."""
    height, width = sim.config.camera.height, sim.config.camera.width
    if looks:
        ids = sim.render_instance_ids(state)
    else:
        ids = np.broadcast_to(np.zeros(1, np.int32), (height, width))
    return Frame(
        rgb=np.broadcast_to(np.zeros(1, np.uint8), (height, width, 3)),
        depth=np.broadcast_to(np.zeros(1, np.float32), (height, width)),
        instance_ids=ids,
    )
