"""Route answers at three granularities: the heading to the target, the next few metres of
the way there, and the next action.

The path description follows the reference oracle (docs/reference-facts.md §4): the shortest path to
the nearest goal view point (nearest to the agent, by walking distance), its first 4 m,
waypoints at least 1 m apart, a turn wherever the heading changes by more than 40 degrees,
anchored to the nearest landmark in the same room, and a room change wherever the path
enters another room. Rooms are found by sampling the path every 10 cm, so a room crossed
between two waypoints is still named.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from vlln.errors import NavigationError
from vlln.oracle.classify import QuestionAnalysis, StepChoice
from vlln.oracle.knowledge import EpisodeKnowledge, choose, object_phrase, room_name
from vlln.sim.agent import Action, AgentState
from vlln.sim.storey_field import StoreyField
from vlln.world.frame import wrap_angle, yaw_of
from vlln.world.model import ObjectInstance, Room

ROUTE_HORIZON = 4.0  # m of the path that a path answer describes
WAYPOINT_SPACING = 1.0  # m between kept waypoints
TURN_THRESHOLD_DEG = 40.0  # a heading change above this is a turn
ROOM_SAMPLE_SPACING = 0.1  # m between the points tested for a room change
LANDMARK_REACH = 3.0  # m from a turn to the landmark it is anchored to
_MERGE = 0.5  # m: events closer than this share a numbered step
NEXT_TO = 0.3  # m from the target's footprint: "it is right next to you"
STAIRS_NEAR = 1.0  # m: a step answer this close to stairs says "go upstairs" / "downstairs"
_ON_STAIRS = 0.05  # m of height change that means the way is on stairs
CANNOT_ANSWER = "Sorry, I cannot answer your question now."


@dataclass(frozen=True)
class PathEvent:
    """A turn or a room entry, at ``distance`` metres along the path."""

    distance: float
    turn_deg: float = 0.0  # signed, left positive; 0 for a room entry
    room: Room | None = None  # the room entered
    landmark: ObjectInstance | None = None  # what a turn is anchored to


@dataclass(frozen=True)
class PathDescription:
    """The first metres of the shortest path to the target, as a person would tell them."""

    opening_deg: float  # signed angle from the heading to the first leg, left positive
    events: tuple[PathEvent, ...]
    described: float  # metres described (at most ROUTE_HORIZON)
    remaining: float  # metres of the path after the described part


def signed_degrees(knowledge: EpisodeKnowledge, state: AgentState) -> float:
    """Signed angle (left positive) from the heading to the straight line to the target."""
    x, _, z = state.position
    cx, _, cz = knowledge.target.box.center
    return math.degrees(wrap_angle(yaw_of(cx - x, cz - z) - state.yaw))


def answer_orientation(knowledge: EpisodeKnowledge, state: AgentState) -> str:
    """The turn toward the target, rounded to 10 degrees: "Turn left about 60 degrees."."""
    x, _, z = state.position
    category = knowledge.target.category
    rng = knowledge.rng
    angle = _round10(signed_degrees(knowledge, state))
    if angle == 0:
        words = choose(rng, ("It is straight ahead.", f"The {category} is straight ahead of you."))
    elif abs(angle) >= 170:
        words = choose(rng, ("It is behind you.", f"The {category} is behind you; turn around."))
    else:
        side = "left" if angle > 0 else "right"
        turn = f"turn {side} about {abs(angle)} degrees"
        words = choose(
            rng,
            (
                f"{turn.capitalize()}.",
                f"It is to your {side}: {turn}.",
                f"{turn.capitalize()} to face it.",
            ),
        )
    storey = _other_storey(knowledge, state)
    if storey:
        return f"It is {storey}, take the stairs. {words}"
    if knowledge.plan_distance(x, z) < NEXT_TO:
        return f"It is right next to you. {words}"
    return words


def _other_storey(knowledge: EpisodeKnowledge, state: AgentState) -> str:
    """ "upstairs" or "downstairs" when the target is on another storey, else ""."""
    here = knowledge.index.storey_at(state.position[1])
    room = knowledge.target_room
    if here is None or room is None or room.level == here:
        return ""
    return "upstairs" if room.level > here else "downstairs"


def answer_step(knowledge: EpisodeKnowledge, analysis: QuestionAnalysis, state: AgentState) -> str:
    """The follower's next action in words, as a yes or no when the question proposed one."""
    try:
        action = knowledge.follower.next_action(state)
    except NavigationError:
        return CANNOT_ANSWER
    words = choose(knowledge.rng, _ACTION_WORDS[action])
    stairs = stairs_ahead(knowledge, state, STAIRS_NEAR)
    if stairs is not None and action != Action.STOP:
        way = _STAIRS_WORD[stairs[1]]
        if action == Action.MOVE_FORWARD:
            words = choose(knowledge.rng, (f"Go {way}.", f"Go forward and {way}."))
        else:
            words = f"{words[:-1]}, then go {way}."
    proposed = analysis.step_choice
    if proposed is None:
        return words
    agrees = _CHOICE_ACTION[proposed] == action
    return f"{'Yes' if agrees else 'No'}, {words[0].lower()}{words[1:]}"


_ACTION_WORDS: dict[Action, tuple[str, ...]] = {
    Action.STOP: ("You are there.", "You are there, you can stop."),
    Action.MOVE_FORWARD: ("Go forward.", "Move forward.", "Keep going forward."),
    Action.TURN_LEFT: ("Turn left.", "Turn to the left."),
    Action.TURN_RIGHT: ("Turn right.", "Turn to the right."),
}
_CHOICE_ACTION = {
    StepChoice.LEFT: Action.TURN_LEFT,
    StepChoice.RIGHT: Action.TURN_RIGHT,
    StepChoice.FORWARD: Action.MOVE_FORWARD,
    StepChoice.STOP: Action.STOP,
}


def answer_path(knowledge: EpisodeKnowledge, state: AgentState) -> str:
    """Numbered directions for the next 4 m, closing on the target when it is that close;
    where the way reaches stairs within them, the directions end with "go upstairs" (or
    downstairs) and how far the target is from there."""
    x, y, z = state.position
    distance = knowledge.geodesic(x, z, y)
    if distance == math.inf:
        return CANNOT_ANSWER
    if distance < knowledge.follower.goal_radius:
        return choose(knowledge.rng, ("You are there.", "You are already there."))
    stairs = stairs_ahead(knowledge, state, ROUTE_HORIZON)
    if stairs is not None:
        return _stairs_sentence(knowledge, state, distance, *stairs)
    return path_sentence(knowledge, describe_path(knowledge, state))


def stairs_ahead(
    knowledge: EpisodeKnowledge, state: AgentState, within: float
) -> tuple[float, int] | None:
    """How far along the way the stairs begin and which way they go (+1 up, -1 down), when
    the way takes stairs within ``within`` metres; None on one storey."""
    field = knowledge.field
    if not isinstance(field, StoreyField):
        return None
    x, y, z = state.position
    if not field.is_reachable(x, z, y):
        return None
    travelled, previous = 0.0, (x, y, z)
    for point in field.path_nodes(x, y, z, within):
        travelled += math.dist(previous, point)
        previous = point
        if abs(point[1] - y) > _ON_STAIRS:
            return travelled, 1 if point[1] > y else -1
    return None


def _stairs_sentence(
    knowledge: EpisodeKnowledge, state: AgentState, distance: float, gap: float, way: int
) -> str:
    x, y, z = state.position
    path = knowledge.field.shortest_path(x, z, gap, y)
    opening = 0.0
    if len(path) >= 2:
        dx, dz = path[1][0] - path[0][0], path[1][1] - path[0][1]
        opening = math.degrees(wrap_angle(yaw_of(dx, dz) - state.yaw))
    word = _STAIRS_WORD[way]
    step = _with_forward(gap, f"go {word}") if gap >= _MERGE else f"go {word}"
    category = knowledge.target.category
    further = _metres(max(0.0, distance - gap))
    return (
        f"{_opening(opening, knowledge.rng)} 1. {step[0].upper()}{step[1:]} by the stairs. "
        f"From there the {category} is still {further} away."
    )


_STAIRS_WORD = {1: "upstairs", -1: "downstairs"}


def describe_path(knowledge: EpisodeKnowledge, state: AgentState) -> PathDescription:
    """The turns and room entries of the first :data:`ROUTE_HORIZON` metres of the path."""
    x, y, z = state.position
    path = np.asarray(knowledge.field.shortest_path(x, z, ROUTE_HORIZON, y), np.float64)
    legs = np.linalg.norm(np.diff(path, axis=0), axis=1)
    arc = np.concatenate([[0.0], np.cumsum(legs)])
    # A prefix was traced when the way is long: the rest is the geodesic distance left.
    total = (
        float(arc[-1])
        if arc[-1] <= ROUTE_HORIZON
        else max(float(arc[-1]), knowledge.geodesic(x, z, y))
    )
    cut = _cut(path, arc, ROUTE_HORIZON)
    arc_cut = [*arc[: len(cut) - 1].tolist(), min(total, ROUTE_HORIZON)]
    waypoints, where = _waypoints(cut, arc_cut)
    events: list[PathEvent] = []
    for i in range(1, len(waypoints) - 1):
        turn = _turn_deg(waypoints[i - 1], waypoints[i], waypoints[i + 1])
        if abs(turn) > TURN_THRESHOLD_DEG:
            landmark = _landmark(knowledge, waypoints[i], y)
            events.append(PathEvent(where[i], turn, None, landmark))
    events.extend(_room_entries(knowledge, cut, arc_cut, y))
    events.sort(key=lambda e: e.distance)
    opening = 0.0
    if len(waypoints) >= 2:
        dx, dz = waypoints[1] - waypoints[0]
        opening = math.degrees(wrap_angle(yaw_of(float(dx), float(dz)) - state.yaw))
    described = arc_cut[-1]
    return PathDescription(opening, tuple(events), described, max(0.0, total - described))


def path_sentence(knowledge: EpisodeKnowledge, description: PathDescription) -> str:
    """The description in words: "Turn left about 60 degrees. 1. Go forward about 2 meters
    and enter the kitchen. 2. ..."."""
    category = knowledge.target.category
    rng = knowledge.rng
    sentences = [_opening(description.opening_deg, rng)]
    groups: list[list[PathEvent]] = []
    for event in description.events:
        if groups and event.distance - groups[-1][0].distance < _MERGE:
            groups[-1].append(event)
        else:
            groups.append([event])
    steps: list[str] = []
    travelled = 0.0
    for group in groups:
        phrases = [_event_phrase(event) for event in group]
        steps.append(_with_forward(group[0].distance - travelled, " and ".join(phrases)))
        travelled = group[0].distance
    tail = description.described - travelled
    if description.remaining <= 0.05:
        arrival = choose(
            rng, (f"the {category} will be right there", f"you will reach the {category}")
        )
        steps.append(_with_forward(tail, arrival, joiner="; "))
    elif tail >= _MERGE:
        steps.append(_with_forward(tail, ""))
    numbered = [f"{n}. {step[0].upper()}{step[1:]}." for n, step in enumerate(steps, 1)]
    sentences.extend(numbered)
    if description.remaining > 0.05:
        further = _metres(description.remaining)
        sentences.append(f"From there the {category} is still {further} away.")
    return " ".join(sentences)


def _opening(angle: float, rng: np.random.Generator) -> str:
    if abs(angle) >= 120.0:
        return choose(rng, ("Turn around.", "First turn around."))
    if abs(angle) > 20.0:
        side = "left" if angle > 0 else "right"
        return f"Turn {side} about {abs(_round10(angle))} degrees."
    return choose(rng, ("Go straight ahead.", "Start straight ahead."))


def _event_phrase(event: PathEvent) -> str:
    if event.room is not None:
        return f"enter the {room_name(event.room)}"
    side = "left" if event.turn_deg > 0 else "right"
    if event.landmark is None:
        return f"turn {side}"
    return f"turn {side} at {object_phrase(event.landmark)}"


def _with_forward(gap: float, then: str, joiner: str = " and ") -> str:
    """Prefixes "go forward about 2 meters and"; short gaps are not worth saying."""
    if gap < _MERGE:
        return then or "go forward a little"
    forward = f"go forward {_metres(gap)}"
    return f"{forward}{joiner}{then}" if then else forward


def _metres(distance: float) -> str:
    whole = max(1, round(distance))
    return f"about {whole} meter" + ("s" if whole > 1 else "")


def _round10(degrees: float) -> int:
    return round(degrees / 10.0) * 10


def _cut(path: np.ndarray, arc: np.ndarray, horizon: float) -> np.ndarray:
    """The polyline up to ``horizon`` metres, ending exactly there when it is longer."""
    if arc[-1] <= horizon:
        return path
    k = int(np.searchsorted(arc, horizon))  # arc[k - 1] < horizon <= arc[k]
    t = (horizon - arc[k - 1]) / (arc[k] - arc[k - 1])
    end = path[k - 1] + t * (path[k] - path[k - 1])
    return np.vstack([path[:k], end])


def _waypoints(points: np.ndarray, arc: list[float]) -> tuple[list[np.ndarray], list[float]]:
    """Start, corners at least :data:`WAYPOINT_SPACING` from the previous kept one, end."""
    kept = [points[0]]
    where = [0.0]
    for point, distance in zip(points[1:-1], arc[1:-1], strict=True):
        if np.linalg.norm(point - kept[-1]) >= WAYPOINT_SPACING:
            kept.append(point)
            where.append(distance)
    if len(kept) == 1 or np.linalg.norm(points[-1] - kept[-1]) >= 0.25:
        kept.append(points[-1])
        where.append(arc[-1])
    return kept, where


def _turn_deg(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> float:
    before = yaw_of(float(b[0] - a[0]), float(b[1] - a[1]))
    after = yaw_of(float(c[0] - b[0]), float(c[1] - b[1]))
    return math.degrees(wrap_angle(after - before))


def _landmark(knowledge: EpisodeKnowledge, point: np.ndarray, y: float) -> ObjectInstance | None:
    """The nearest landmark in the point's room, not of the target's category."""
    x, z = float(point[0]), float(point[1])
    room = knowledge.index.room_at(x, z, y)
    if room is None:
        return None
    best: tuple[float, ObjectInstance] | None = None
    for inst in knowledge.index.landmarks.get(room.id, []):
        if inst.category == knowledge.target.category:
            continue
        box = inst.box
        gap = box.plan_distance(x, z)
        if gap <= LANDMARK_REACH and (best is None or gap < best[0]):
            best = (gap, inst)
    return None if best is None else best[1]


def _room_entries(
    knowledge: EpisodeKnowledge, points: np.ndarray, arc: list[float], y: float
) -> list[PathEvent]:
    """A room entry wherever a sample of the path lies in a room other than the last one."""
    samples: list[np.ndarray] = []
    where: list[float] = []
    for k in range(len(points) - 1):
        count = max(1, math.ceil((arc[k + 1] - arc[k]) / ROOM_SAMPLE_SPACING))
        for i in range(count):
            t = i / count
            samples.append(points[k] + t * (points[k + 1] - points[k]))
            where.append(arc[k] + t * (arc[k + 1] - arc[k]))
    samples.append(points[-1])
    where.append(arc[-1])
    rooms = knowledge.index.rooms_at(np.array(samples), y)
    start = knowledge.index.room_at(float(points[0][0]), float(points[0][1]), y)
    current = -1 if start is None else start.id
    events = []
    for room_id, distance in zip(rooms.tolist(), where, strict=True):
        if room_id >= 0 and room_id != current:
            events.append(PathEvent(distance, room=knowledge.index.house.room(room_id)))
            current = room_id
    return events
