"""Answers checked against the geometry and metadata of a generated house."""

from __future__ import annotations

import itertools
import math
import re
from collections.abc import Iterator
from dataclasses import replace

import numpy as np
import pytest
from matplotlib.path import Path as PolygonPath

from vlln.oracle.rule_oracle import RuleOracle
from vlln.sim.agent import Action, AgentState
from vlln.sim.camera import CameraSpec
from vlln.sim.follower import GreedyFollower
from vlln.sim.renderer import Frame
from vlln.sim.simulator import Simulator, SimulatorConfig
from vlln.sim.viewpoints import view_points
from vlln.tasks.oracle_protocol import EpisodeContext, Question, QuestionType
from vlln.world.catalogue.aliases import ALIASES
from vlln.world.frame import wrap_angle, yaw_of
from vlln.world.generator import generate_house
from vlln.world.model import ObjectInstance, Room

HOUSE_SEED = 1
CANNOT = "Sorry, I cannot answer your question now."
LOOK_DOWN = -math.radians(30.0)


@pytest.fixture(scope="module")
def sim() -> Iterator[Simulator]:
    # A quarter-size camera: the disambiguation rule works on image fractions, renders are 4x
    # faster.
    camera = CameraSpec(width=320, height=240)
    simulator = Simulator(generate_house(HOUSE_SEED), SimulatorConfig(camera=camera))
    yield simulator
    simulator.close()


def _goals(sim: Simulator, target: ObjectInstance) -> tuple[tuple[float, float], ...]:
    return tuple(view_points(sim.grid, target.box))


def _oracle(
    sim: Simulator, target: ObjectInstance, seed: int = 0, cues: bool = False
) -> RuleOracle:
    oracle = RuleOracle(seed, cues=cues)
    oracle.start(EpisodeContext(sim, target, _goals(sim, target)))
    return oracle


def _blank(sim: Simulator) -> Frame:
    spec = sim.config.camera
    return Frame(
        np.zeros((spec.height, spec.width, 3), np.uint8),
        np.zeros((spec.height, spec.width), np.float32),
        np.zeros((spec.height, spec.width), np.int32),
    )


def _ask(
    oracle: RuleOracle, sim: Simulator, state: AgentState, text: str, look: bool = False
) -> str:
    frame = sim.render(state) if look else _blank(sim)
    return oracle.answer(Question(text, state, frame)).answer


def _reachable_targets(
    sim: Simulator, count: int, rng: np.random.Generator
) -> list[ObjectInstance]:
    """Targets whose view points the largest navigable component reaches."""
    component = sim.grid.largest_component()
    found = []
    for index in rng.permutation(len(sim.house.instances)):
        target = sim.house.instances[int(index)]
        goals = _goals(sim, target)
        if goals and any(sim.grid.component_of(x, z) == component for x, z in goals):
            found.append(target)
        if len(found) == count:
            break
    return found


def _states(
    sim: Simulator, goals: tuple[tuple[float, float], ...], rng: np.random.Generator, n: int
) -> list[AgentState]:
    """Random reachable states with random headings."""
    component = sim.grid.largest_component()
    field = sim.geodesic_field(goals)
    states: list[AgentState] = []
    while len(states) < n:
        x, z = sim.grid.sample_navigable_point(rng, component)
        if field.distance(x, z) < math.inf:
            states.append(AgentState((x, 0.0, z), float(rng.uniform(-math.pi, math.pi))))
    return states


def _room_containing(rooms: list[Room], x: float, z: float) -> Room | None:
    inside = [room for room in rooms if PolygonPath(room.polygon).contains_point((x, z))]
    return inside[0] if len(inside) == 1 else None


# --- route ---------------------------------------------------------------------------------


def _said_angle(answer: str) -> float:
    turn = re.search(r"\b(left|right) about (\d+) degrees", answer)
    if turn:
        return float(turn[2]) * (1.0 if turn[1] == "left" else -1.0)
    if "straight ahead" in answer:
        return 0.0
    assert "behind you" in answer, answer
    return 180.0


def test_orientation_answers_the_side_and_angle_of_the_target(sim: Simulator) -> None:
    rng = np.random.default_rng(1)
    for target in _reachable_targets(sim, 4, rng):
        oracle = _oracle(sim, target)
        cx, _, cz = target.box.center
        for state in _states(sim, _goals(sim, target), rng, 40):
            x, _, z = state.position
            if math.hypot(cx - x, cz - z) < 0.5:
                continue  # the direction to the centre is ill-defined
            answer = _ask(oracle, sim, state, "Which direction is the target?")
            truth = math.degrees(wrap_angle(yaw_of(cx - x, cz - z) - state.yaw))
            error = abs(math.remainder(_said_angle(answer) - truth, 360.0))
            assert error <= 15.0, (answer, truth)


def test_orientation_left_is_counter_clockwise_seen_from_above(sim: Simulator) -> None:
    target = sim.house.instances[0]
    oracle = _oracle(sim, target)
    cx, _, cz = target.box.center
    # Looking along -z (yaw 0), the target 3 m toward -x is on the left.
    answer = _ask(oracle, sim, AgentState((cx + 3.0, 0.0, cz), 0.0), "Which way is it?")
    assert re.search(r"left about 90 degrees", answer), answer
    answer = _ask(oracle, sim, AgentState((cx - 3.0, 0.0, cz), 0.0), "Which way is it?")
    assert re.search(r"right about 90 degrees", answer), answer
    assert "straight ahead" in _ask(oracle, sim, AgentState((cx, 0.0, cz + 3.0), 0.0), "Which way?")
    assert "behind you" in _ask(oracle, sim, AgentState((cx, 0.0, cz - 3.0), 0.0), "Which way?")


_ACTION_WORDS = {
    "you are there": Action.STOP,
    "forward": Action.MOVE_FORWARD,
    "left": Action.TURN_LEFT,
    "right": Action.TURN_RIGHT,
}


def _said_action(answer: str) -> Action:
    said = [action for words, action in _ACTION_WORDS.items() if words in answer.lower()]
    assert len(said) == 1, answer
    return said[0]


def test_step_answers_are_the_followers_next_action(sim: Simulator) -> None:
    rng = np.random.default_rng(2)
    seen = set()
    for target in _reachable_targets(sim, 3, rng):
        oracle = _oracle(sim, target)
        goals = _goals(sim, target)
        follower = GreedyFollower(sim.grid, sim.geodesic_field(goals), 0.25, sim.config.motion)
        for state in _states(sim, goals, rng, 25):
            expected = follower.next_action(state)
            seen.add(expected)
            assert _said_action(_ask(oracle, sim, state, "What should I do next?")) == expected
            proposed = _ask(oracle, sim, state, "Should I turn left?")
            assert proposed.startswith("Yes" if expected == Action.TURN_LEFT else "No"), proposed
            assert _said_action(proposed) == expected
    assert {Action.MOVE_FORWARD, Action.TURN_LEFT, Action.TURN_RIGHT} <= seen


def test_step_answer_at_a_view_point_is_you_are_there(sim: Simulator) -> None:
    target = _reachable_targets(sim, 1, np.random.default_rng(3))[0]
    x, z = _goals(sim, target)[0]
    answer = _ask(_oracle(sim, target), sim, AgentState((x, 0.0, z), 0.0), "Next step?")
    assert _said_action(answer) == Action.STOP


def _rooms_entered(
    sim: Simulator, state: AgentState, goals: tuple[tuple[float, float], ...], horizon: float
) -> list[str]:
    """Room types the first ``horizon`` metres of the shortest path enter, every 2 cm."""
    x, _, z = state.position
    path = np.array(sim.geodesic_field(goals).shortest_path(x, z))
    samples = []
    travelled = 0.0
    for a, b in itertools.pairwise(path):
        length = float(np.linalg.norm(b - a))
        for t in np.arange(0.0, length, 0.02):
            if travelled + t <= horizon:
                samples.append(a + (b - a) * (t / length))
        travelled += length
    rooms = sim.house.rooms
    inside = np.array([PolygonPath(room.polygon).contains_points(samples) for room in rooms])
    entered: list[str] = []
    current = _room_containing(rooms, x, z)
    for column in inside.T:
        if np.count_nonzero(column) != 1:
            continue  # on a wall between two rooms
        room = rooms[int(np.argmax(column))]
        if current is not None and room.id != current.id:
            entered.append(room.type)
        current = room
    return entered


def test_path_answers_name_the_rooms_entered_in_order(sim: Simulator) -> None:
    rng = np.random.default_rng(4)
    crossings = 0
    for target in _reachable_targets(sim, 4, rng):
        oracle = _oracle(sim, target)
        goals = _goals(sim, target)
        field = sim.geodesic_field(goals)
        for state in _states(sim, goals, rng, 20):
            x, _, z = state.position
            if field.distance(x, z) < 0.25 or _room_containing(sim.house.rooms, x, z) is None:
                continue
            answer = _ask(oracle, sim, state, "How do I get there?")
            named = re.findall(r"enter the ([a-z ]+?)(?: and |[.;,])", answer.lower())
            # A room entered right at the 4 m cut may be named or not.
            surely = _rooms_entered(sim, state, goals, 3.95)
            maybe = _rooms_entered(sim, state, goals, 4.05)
            assert named[: len(surely)] == surely and named == maybe[: len(named)], answer
            crossings += len(named)
            steps = re.findall(r"\b(\d+)\. ", answer)
            assert steps == [str(n) for n in range(1, len(steps) + 1)], answer
            path = np.array(field.shortest_path(x, z))
            length = float(np.sum(np.linalg.norm(np.diff(path, axis=0), axis=1)))
            if length <= 3.95:
                assert re.search(r"right there|you will reach", answer, re.IGNORECASE), answer
            elif length > 4.05:
                assert "still about" in answer, answer
    assert crossings >= 5


# --- disambiguation ------------------------------------------------------------------------


def _centre(ids: np.ndarray) -> np.ndarray:
    h, w = ids.shape
    return ids[h // 4 : 3 * h // 4, w // 4 : 3 * w // 4]


def _facing_views(
    sim: Simulator, instance: ObjectInstance, near: float, far: float, rng: np.random.Generator
) -> Iterator[tuple[AgentState, Frame]]:
    """States ``near``..``far`` m from the instance, facing it, whose central region shows it
    more than any other object, over at least a tenth of the region."""
    grid = sim.grid
    rows, cols = np.nonzero(grid.navigable)
    ox, oz = grid.origin
    xs = ox + (cols + 0.5) * grid.cell_size
    zs = oz + (rows + 0.5) * grid.cell_size
    box = instance.box
    gap = np.hypot(
        np.maximum.reduce([box.min[0] - xs, np.zeros_like(xs), xs - box.max[0]]),
        np.maximum.reduce([box.min[2] - zs, np.zeros_like(zs), zs - box.max[2]]),
    )
    candidates = np.nonzero((gap >= near) & (gap <= far))[0]
    cx, _, cz = box.center
    for k in rng.permutation(candidates)[:30]:
        x, z = float(xs[k]), float(zs[k])
        for tilt in (0.0, LOOK_DOWN):
            state = AgentState((x, 0.0, z), yaw_of(cx - x, cz - z), tilt)
            frame = sim.render(state)
            centre = _centre(frame.instance_ids)
            objects = np.bincount(centre[centre > 0].ravel())
            if (
                len(objects)
                and int(np.argmax(objects)) == instance.id
                and (objects[instance.id] >= 0.1 * centre.size)
            ):
                yield state, frame
                break


def _same_category_pairs(sim: Simulator) -> Iterator[tuple[ObjectInstance, ObjectInstance]]:
    """Pairs of large instances of one category with clearly different colours."""
    by_category: dict[str, list[ObjectInstance]] = {}
    for inst in sim.house.instances:
        if max(inst.box.size) >= 0.6 and inst.attributes.color:
            by_category.setdefault(inst.category, []).append(inst)
    for group in by_category.values():
        for a in group:
            for b in group:
                if (
                    a.attributes.color not in b.attributes.color
                    and b.attributes.color not in a.attributes.color
                ):
                    yield a, b


def test_disambiguation_yes_when_facing_the_target_nearby(sim: Simulator) -> None:
    rng = np.random.default_rng(5)
    checked = 0
    for target, _ in _same_category_pairs(sim):
        oracle = _oracle(sim, target)
        for state, frame in itertools.islice(_facing_views(sim, target, 0.4, 2.5, rng), 2):
            reply = oracle.answer(Question("Is this the one?", state, frame))
            assert reply.question_type == QuestionType.DISAMBIGUATION
            assert reply.answer.startswith("Yes"), reply.answer
            # Facing away from it, it is not in view at all.
            away = AgentState(state.position, state.yaw + math.pi, state.tilt)
            away_frame = sim.render(away)
            assert not np.any(away_frame.instance_ids == target.id)
            answer = oracle.answer(Question("Is this the one?", away, away_frame)).answer
            assert answer.startswith("No"), answer
            checked += 1
        if checked >= 4:
            break
    assert checked >= 4


def test_disambiguation_no_when_the_target_is_centred_but_far(sim: Simulator) -> None:
    rng = np.random.default_rng(6)
    # Tall objects (wardrobes, curtains) stay visible over furniture from across a room.
    large = sorted(
        (inst for inst in sim.house.instances if inst.box.size[1] >= 1.7),
        key=lambda inst: -inst.box.size[1],
    )
    checked = 0
    for target in large:
        oracle = _oracle(sim, target)
        for state, frame in _facing_views(sim, target, 3.3, 8.0, rng):
            answer = oracle.answer(Question("Is it this one?", state, frame)).answer
            assert answer.startswith("No"), answer
            checked += 1
            break
        if checked == 2:
            break
    assert checked == 2, "no distant view of a large object found"


def test_disambiguation_no_with_a_distinguishing_colour_for_a_distractor(sim: Simulator) -> None:
    rng = np.random.default_rng(7)
    checked = 0
    for target, distractor in _same_category_pairs(sim):
        oracle = _oracle(sim, target, cues=True)
        for state, frame in itertools.islice(_facing_views(sim, distractor, 0.4, 2.5, rng), 2):
            if np.any(_centre(frame.instance_ids) == target.id):
                continue
            answer = oracle.answer(Question("Is this the right one?", state, frame)).answer
            assert answer.startswith("No"), answer
            assert target.attributes.color in answer, answer
            assert distractor.attributes.color not in answer, answer
            checked += 1
        if checked >= 2:
            break
    assert checked >= 2


# --- attributes ----------------------------------------------------------------------------


def _described_targets(sim: Simulator) -> list[ObjectInstance]:
    rng = np.random.default_rng(8)
    return [t for t in _reachable_targets(sim, 12, rng) if t.attributes.color]


def test_attribute_answers_state_the_targets_values(sim: Simulator) -> None:
    for target in _described_targets(sim):
        oracle = _oracle(sim, target)
        attrs = target.attributes
        x, z = _goals(sim, target)[0]
        state = AgentState((x, 0.0, z), 0.0)
        room = sim.house.room(target.room_id)
        assert attrs.color in _ask(oracle, sim, state, "What colour is it?")
        material = _ask(oracle, sim, state, "What is it made of?")
        if attrs.material not in ("plain", "foliage"):
            assert f"made of {attrs.material}" in material
        assert room.type in _ask(oracle, sim, state, "Which room is it in?")
        assert attrs.size in _ask(oracle, sim, state, "How big is it?")
        fine = target.fine_category or target.category
        assert fine in _ask(oracle, sim, state, f"What kind of {target.category} is it?")
        described = _ask(oracle, sim, state, "Can you describe it?")
        assert attrs.color in described and room.type in described, described
        if attrs.material not in ("plain", "foliage"):
            assert attrs.material in described, described


def test_yes_no_attribute_questions_confirm_or_correct(sim: Simulator) -> None:
    for target in _described_targets(sim):
        oracle = _oracle(sim, target)
        color = target.attributes.color
        x, z = _goals(sim, target)[0]
        state = AgentState((x, 0.0, z), 0.0)
        assert _ask(oracle, sim, state, f"Is it {color}?").startswith("Yes")
        other = next(c for c in ("purple", "teal", "orange") if c not in color)
        wrong = _ask(oracle, sim, state, f"Is it {other}?")
        assert wrong.startswith("No") and color in wrong, wrong
        here = _ask(oracle, sim, state, "Is it in this room?")
        in_room = _room_containing(sim.house.rooms, x, z)
        if in_room is not None:
            assert here.startswith("Yes" if in_room.id == target.room_id else "No"), here


def test_relation_answers_name_real_neighbours(sim: Simulator) -> None:
    house = sim.house
    checked = 0
    for target in _described_targets(sim):
        related = {
            house.instance(r.object).category for r in house.relations if r.subject == target.id
        }
        if not related:
            continue
        oracle = _oracle(sim, target)
        answer = _ask(oracle, sim, AgentState((0.0, 0.0, 0.0)), "What is near it?")
        assert any(category in answer for category in related), (answer, related)
        checked += 1
    supported = [t for t in house.instances if t.support_id is not None and _goals(sim, t)][:5]
    for target in supported:
        oracle = _oracle(sim, target)
        support = house.instance(target.support_id or 0)
        answer = _ask(oracle, sim, AgentState((0.0, 0.0, 0.0)), "What is it sitting on?")
        assert support.category in answer, answer
        checked += 1
    assert checked >= 5


@pytest.mark.slow
def test_relation_questions_may_name_a_category_by_its_earlier_name(sim: Simulator) -> None:
    house = sim.house
    earlier = {name: alias for alias, name in ALIASES.items()}
    asked = 0
    for relation in house.relations:
        target, other = house.instance(relation.subject), house.instance(relation.object)
        if other.category not in earlier or not _goals(sim, target):
            continue
        oracle = _oracle(sim, target)
        question = f"Is it {relation.word} the {earlier[other.category]}?"
        answer = _ask(oracle, sim, AgentState((0.0, 0.0, 0.0)), question)
        assert answer.startswith("Yes") and other.category in answer, (question, answer)
        asked += 1
    assert asked >= 3


def test_unknown_attributes_are_not_invented(sim: Simulator) -> None:
    target = _described_targets(sim)[0]
    blank = replace(target, attributes=replace(target.attributes, color="", material=""))
    oracle = RuleOracle()
    oracle.start(EpisodeContext(sim, blank, _goals(sim, target)))
    state = AgentState((0.0, 0.0, 0.0))
    assert _ask(oracle, sim, state, "What color is it?") == "I don't know."
    assert _ask(oracle, sim, state, "What material is it?") == "I don't know."


# --- other ---------------------------------------------------------------------------------


def test_other_answers_use_the_agents_state(sim: Simulator) -> None:
    rng = np.random.default_rng(9)
    target = _reachable_targets(sim, 1, rng)[0]
    oracle = _oracle(sim, target)
    goals = _goals(sim, target)
    field = sim.geodesic_field(goals)
    for state in _states(sim, goals, rng, 30):
        x, _, z = state.position
        room = _room_containing(sim.house.rooms, x, z)
        if room is not None:
            assert room.type in _ask(oracle, sim, state, "What room am I in?")
        distance = field.distance(x, z)
        if distance < 0.25:
            continue
        far = _ask(oracle, sim, state, "How far is it?")
        said = re.search(r"about (\d+) meter", far)
        if said:
            assert abs(int(said[1]) - distance) <= 0.5 + 1e-9, (far, distance)
        else:
            assert "less than a meter" in far and distance < 1.0, (far, distance)
        close = _ask(oracle, sim, state, "Am I close?")
        assert ("close" in close) == (distance <= 3.0), (close, distance)
        assert _ask(oracle, sim, state, "What time is it?") == CANNOT


def test_visibility_answers_follow_the_frame(sim: Simulator) -> None:
    rng = np.random.default_rng(10)
    target, _ = next(_same_category_pairs(sim))
    oracle = _oracle(sim, target)
    seen = []
    views = [
        view for view, _ in zip(_facing_views(sim, target, 0.4, 2.5, rng), range(2), strict=False)
    ]
    states = [state for state, _ in views] + _states(sim, _goals(sim, target), rng, 10)
    for state in states:
        frame = sim.render(state)
        visible = (
            np.count_nonzero(frame.instance_ids == target.id) > 0.0002 * frame.instance_ids.size
        )
        answer = oracle.answer(Question("Can I see it?", state, frame)).answer
        assert answer.startswith("Yes" if visible else "No"), answer
        seen.append(visible)
    assert any(seen) and not all(seen)
