"""The helpful oracle on a generated house: each kind of help checked against the house's
geometry and the rendered view, the paper's answers unchanged, and its replies carried
through the environment into episode records."""

from __future__ import annotations

import math
from collections import Counter

import numpy as np
import pytest
from matplotlib.path import Path as PolygonPath

from tests.oracle.episodes import iign_episode
from tests.oracle.test_answers import _blank
from tests.oracle.test_rule_oracle import QUESTIONS, _states
from vlln.errors import ConfigError
from vlln.eval.ablation import switch_values
from vlln.eval.config import EvalConfig
from vlln.eval.runner import default_provenance
from vlln.oracle.answers import VISIBLE_MIN_SHARE
from vlln.oracle.classifier.entities import object_names
from vlln.oracle.helpful.oracle import HelpfulOracle
from vlln.oracle.rule_oracle import TYPE_REFUSAL, RuleOracle
from vlln.oracle.settings import OracleBackend, OracleSettings
from vlln.sim.agent import Action, AgentState
from vlln.sim.follower import GreedyFollower
from vlln.sim.renderer import Frame
from vlln.sim.simulator import Simulator
from vlln.sim.viewpoints import storey_view_points, view_points
from vlln.tasks.env import NavigationEnv
from vlln.tasks.oracle_protocol import EpisodeContext, Question, QuestionType, Reply
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.scenes import SceneCache, procedural_scene_id
from vlln.tasks.spec import Talk, TaskConfig
from vlln.world.frame import yaw_of
from vlln.world.generator.furnishing import WINDOW_COVERINGS
from vlln.world.model import ObjectInstance

Point = tuple[float, float, float]


def _started(
    oracle: HelpfulOracle | RuleOracle, sim: Simulator, target: ObjectInstance
) -> HelpfulOracle | RuleOracle:
    oracle.start(EpisodeContext(sim, target, tuple(view_points(sim.grid, target.box))))
    return oracle


def _ask(
    oracle: HelpfulOracle | RuleOracle,
    state: AgentState,
    frame: Frame,
    text: str,
    path: tuple[Point, ...] = (),
) -> Reply:
    return oracle.answer(Question(text, state, frame, path))


def _visible(sim: Simulator, frame: Frame, category: str) -> dict[int, float]:
    """Instances of ``category`` in view (as many pixels as "in your view" needs), by the
    mean column of their pixels as a fraction of the width."""
    ids = frame.instance_ids
    shown = {}
    for inst in sim.house.instances_of(category):
        columns = np.nonzero(ids == inst.id)[1]
        if len(columns) >= VISIBLE_MIN_SHARE * ids.size:
            shown[inst.id] = float(columns.mean()) / ids.shape[1]
    return shown


def _gap(inst: ObjectInstance, state: AgentState) -> float:
    x, _, z = state.position
    box = inst.box
    return math.hypot(
        max(box.min[0] - x, 0.0, x - box.max[0]), max(box.min[2] - z, 0.0, z - box.max[2])
    )


@pytest.fixture(scope="module")
def chair(sim: Simulator) -> ObjectInstance:
    """A chair of the room with most chairs (the dining room's), the first by id."""
    rooms = Counter(inst.room_id for inst in sim.house.instances_of("chair"))
    room, count = rooms.most_common(1)[0]
    assert count >= 3, "the test house needs a room with several chairs"
    return min(
        (inst for inst in sim.house.instances_of("chair") if inst.room_id == room),
        key=lambda inst: inst.id,
    )


@pytest.fixture(scope="module")
def views(sim: Simulator, chair: ObjectInstance) -> list[tuple[AgentState, Frame]]:
    """Seeded views from around the chair's room, facing near it, that show two or more
    chairs, three or more of them exactly two with the chair among them."""
    rng = np.random.default_rng(11)
    polygon = np.asarray(sim.house.room(chair.room_id).polygon)
    low, high = polygon.min(axis=0) - 1.0, polygon.max(axis=0) + 1.0
    component = sim.grid.largest_component()
    cx, _, cz = chair.box.center
    found: list[tuple[AgentState, Frame]] = []
    pairs = 0
    for _ in range(1500):
        x, z = sim.grid.sample_navigable_point(rng, component)
        if not (low[0] < x < high[0] and low[1] < z < high[1]):
            continue
        state = AgentState((x, 0.0, z), yaw_of(cx - x, cz - z) + float(rng.uniform(-0.5, 0.5)))
        frame = sim.render(state)
        shown = _visible(sim, frame, "chair")
        pair = len(shown) == 2 and chair.id in shown
        if len(shown) >= 2 and (len(found) < 12 or pair):
            found.append((state, frame))
            pairs += pair
        if len(found) >= 12 and pairs >= 3:
            return found
    raise AssertionError("too few views of several chairs")
    return found


# --- the paper's questions -----------------------------------------------------------------


def test_the_papers_questions_get_the_rule_oracles_answers(
    sim: Simulator, chair: ObjectInstance
) -> None:
    """Word for word, whatever help was asked for in between; a clarification only adds."""
    rules = _started(RuleOracle(3), sim, chair)
    helpful = _started(HelpfulOracle(RuleOracle(3)), sim, chair)
    for state in _states(sim, 3, 21):
        frame = sim.render(state)
        for question in QUESTIONS:
            _ask(helpful, state, frame, "Am I getting closer?")
            expected = _ask(rules, state, frame, question)
            reply = _ask(helpful, state, frame, question)
            assert (reply.question_type, reply.backend) == (expected.question_type, "helpful")
            if reply.help_kind == "schema":
                assert reply.answer == expected.answer
            else:
                assert reply.help_kind == "clarification"
                assert reply.answer.startswith(f"{expected.answer} ")


def test_with_several_chairs_in_view_clarifications_and_counts_say_which(
    sim: Simulator, chair: ObjectInstance, views: list[tuple[AgentState, Frame]]
) -> None:
    for state, frame in views:
        rules = _started(RuleOracle(0), sim, chair)
        helpful = _started(HelpfulOracle(RuleOracle(0)), sim, chair)
        expected = _ask(rules, state, frame, "Is this the one?").answer
        reply = _ask(helpful, state, frame, "Is this the one?")
        shown = _visible(sim, frame, "chair")
        words = {2: "Two", 3: "Three", 4: "Four", 5: "Five"}[len(shown)]
        assert reply.help_kind == "clarification"
        assert reply.answer.startswith(f"{expected} {words} chairs are in view")
        assert ("the one I mean is" in reply.answer) == (chair.id in shown)
        count = _ask(helpful, state, frame, "how many chairs can i see from here?")
        assert count.help_kind == "count"
        assert count.answer.startswith(f"{words} chairs are in your view.")
        assert ("One of them is the one I mean" in count.answer) == (chair.id in shown)
    alone = _ask(
        _started(HelpfulOracle(RuleOracle(0)), sim, chair), state, _blank(sim), "Is this the one?"
    )
    assert alone.help_kind == "schema" and alone.answer.startswith("No")


# --- candidates in view --------------------------------------------------------------------


def test_comparison_names_the_side_distance_and_colour_of_the_target(
    sim: Simulator, chair: ObjectInstance, views: list[tuple[AgentState, Frame]]
) -> None:
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, chair)
    checked = 0
    for state, frame in views:
        shown = _visible(sim, frame, "chair")
        if len(shown) != 2 or chair.id not in shown:
            continue
        other = sim.house.instance(next(i for i in shown if i != chair.id))
        left = shown[chair.id] < shown[other.id]
        if abs(shown[chair.id] - shown[other.id]) >= 0.05:
            answer = _ask(
                oracle, state, frame, "is it the one on the left or the one on the right?"
            )
            assert f"the one on the {'left' if left else 'right'}" in answer.answer
            asked = _ask(oracle, state, frame, "Is it the one on the left?").answer
            assert asked.startswith("Yes" if left else "No"), asked
        nearer = _gap(chair, state) < _gap(other, state)
        if abs(_gap(chair, state) - _gap(other, state)) >= 0.3:
            answer = _ask(oracle, state, frame, "the nearer one or the farther one?").answer
            assert f"the {'nearer' if nearer else 'farther'} one" in answer
        mine, theirs = chair.attributes.color, other.attributes.color
        if mine != theirs:
            answer = _ask(oracle, state, frame, f"is it the {theirs} one or the {mine} one?")
            assert answer.answer == f"It is the {mine} one.", answer.answer
            asked = _ask(oracle, state, frame, f"Is it the {theirs} one?").answer
            assert asked == f"No, it is the {mine} one.", asked
        checked += 1
    assert checked >= 3


def test_confirmation_is_sure_only_when_the_view_leaves_no_doubt(
    sim: Simulator, chair: ObjectInstance, views: list[tuple[AgentState, Frame]]
) -> None:
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, chair)
    for state, frame in views:
        shown = _visible(sim, frame, "chair")
        answer = _ask(oracle, state, frame, "Are you sure?").answer
        if chair.id in shown:
            assert answer.startswith("I can't tell which one you mean from here"), answer
        else:
            assert answer.startswith("Yes, I am sure: none of the chairs"), answer
    blank = _ask(oracle, views[0][0], _blank(sim), "are u sure").answer
    room = sim.house.room(chair.room_id).type
    assert blank.startswith("I can't tell from here: no chair is in your view.") and room in blank
    kinds = _ask(oracle, views[0][0], _blank(sim), "dining chair or the office chair?")
    assert kinds.help_kind == "comparison"
    assert f"The one I mean is a {chair.fine_category or 'chair'}, in " in kinds.answer.replace(
        " an ", " a "
    )
    # At a view point of a chair alone in its room, facing it, it is the only chair in view.
    rooms = Counter(inst.room_id for inst in sim.house.instances_of("chair"))
    lone = next(inst for inst in sim.house.instances_of("chair") if rooms[inst.room_id] == 1)
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, lone)
    cx, _, cz = lone.box.center
    for x, z in view_points(sim.grid, lone.box):
        state = AgentState((x, 0.0, z), yaw_of(cx - x, cz - z))
        frame = sim.render(state)
        if set(_visible(sim, frame, "chair")) == {lone.id}:
            reply = _ask(oracle, state, frame, "Are you sure?")
            assert reply.answer == "Yes, I am sure: it is the one in front of you."
            assert (reply.help_kind, reply.question_type) == ("confirmation", "disambiguation")
            return
    raise AssertionError("no view point shows the chair alone")


# --- progress ------------------------------------------------------------------------------


def _walk_to(sim: Simulator, target: ObjectInstance, seed: int) -> list[Point]:
    """The positions of the shortest-path follower from a seeded start 6 m or more away."""
    goals = tuple(view_points(sim.grid, target.box))
    field = sim.distance_field(goals)
    follower = GreedyFollower(sim.nav, field, 0.25, sim.config.motion)
    rng = np.random.default_rng(seed)
    component = sim.grid.largest_component()
    while True:
        x, z = sim.grid.sample_navigable_point(rng, component)
        if 6.0 <= field.distance(x, z) < math.inf:
            break
    sim.reset(AgentState((x, 0.0, z), 0.0))
    walked = [sim.state.position]
    for _ in range(800):
        action = follower.next_action(sim.state)
        if action == Action.STOP:
            return walked
        sim.move(action)
        walked.append(sim.state.position)
    raise AssertionError("the follower did not arrive")


def _back(walked: list[Point], metres: float) -> list[Point]:
    """The walk, then back along it for ``metres``."""
    back, travelled = [*walked], 0.0
    for later, earlier in zip(walked[::-1], walked[-2::-1], strict=False):
        back.append(earlier)
        travelled += math.dist(later, earlier)
        if travelled >= metres:
            return back
    raise AssertionError("the walk is too short to go back along")


def test_passed_and_closer_are_measured_along_the_walked_path(
    sim: Simulator, chair: ObjectInstance
) -> None:
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, chair)
    walked = _walk_to(sim, chair, 4)
    frame = _blank(sim)

    def ask(text: str, path: list[Point]) -> str:
        return _ask(oracle, AgentState(path[-1], 0.0), frame, text, tuple(path)).answer

    on_the_way = walked[: 2 * len(walked) // 3]
    assert ask("Am I getting closer?", on_the_way).startswith("Yes, you are getting closer")
    assert ask("Did I pass it?", on_the_way).startswith("No, you have not passed it")
    gone_by = _back(walked, 3.0)
    assert ask("Did I pass it?", gone_by).startswith("Yes, you passed the chair")
    assert ask("am i getting warmer", gone_by).startswith("No, you are getting farther")
    assert ask("Am I getting closer?", walked[:1]).startswith("You have not moved yet")


def test_lost_gets_where_it_stands_and_the_way_from_there(
    sim: Simulator, chair: ObjectInstance
) -> None:
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, chair)
    start = _walk_to(sim, chair, 5)[0]
    here = next(
        room for room in sim.house.rooms if PolygonPath(room.polygon).contains_point(start[::2])
    )
    reply = _ask(oracle, AgentState(start, 0.0), _blank(sim), "I think I'm lost, can you help?")
    target_room = sim.house.room(chair.room_id).type
    assert reply.answer.startswith(f"You are in the {here.type}; the chair is in the ")
    assert target_room in reply.answer and "From here: " in reply.answer and " 1. " in reply.answer
    assert (reply.help_kind, reply.question_type) == ("reroute", QuestionType.ROUTE)


def _upstairs(scenes: SceneCache) -> tuple[Simulator, HelpfulOracle, tuple[AgentState, AgentState]]:
    """A house of two storeys, the helpful oracle started on a target upstairs, and a place
    to stand on each storey (below, above)."""
    two = scenes.get(procedural_scene_id(2, floors=2))
    storeys = two.storeys
    assert storeys is not None
    upstairs = next(
        inst
        for inst in two.house.instances
        if two.house.room(inst.room_id).level == 1 and storey_view_points(storeys, inst.box)
    )
    oracle = HelpfulOracle(RuleOracle(0))
    oracle.start(EpisodeContext(two, upstairs, tuple(storey_view_points(storeys, upstairs.box))))
    rng = np.random.default_rng(2)
    main = storeys.largest_component()
    at: dict[int, AgentState] = {}
    while len(at) < 2:
        point = storeys.sample_navigable_point(rng, main)
        for level, floor_y in enumerate(storeys.floor_ys[:2]):
            if point[1] == floor_y:
                at.setdefault(level, AgentState(point, 0.0))
    return two, oracle, (at[0], at[1])


def test_floor_answers_in_a_house_of_one_storey_and_of_two(
    sim: Simulator, scenes: SceneCache, chair: ObjectInstance
) -> None:
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, chair)
    state, frame = AgentState(_walk_to(sim, chair, 6)[0], 0.0), _blank(sim)
    assert _ask(oracle, state, frame, "should I go upstairs?").answer.startswith("No. ")
    assert _ask(oracle, state, frame, "Which floor is it on?").answer == (
        "This house has one floor, and it is on it."
    )
    two, oracle, (below, above) = _upstairs(scenes)
    frame = _blank(two)
    assert _ask(oracle, below, frame, "should I go upstairs?").answer == (
        "Yes. It is on the upper floor: go upstairs."
    )
    assert _ask(oracle, below, frame, "Am I on the wrong floor?").answer.startswith("Yes. ")
    assert _ask(oracle, below, frame, "Is it downstairs?").answer.startswith("No. ")
    assert _ask(oracle, above, frame, "should I go upstairs?").answer.startswith("No. ")
    assert _ask(oracle, above, frame, "Which floor is it on?").answer == (
        "It is on the upper floor, the floor you are on."
    )


# --- the house -----------------------------------------------------------------------------


def test_counts_are_the_houses_instances_by_room(sim: Simulator, chair: ObjectInstance) -> None:
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, chair)
    state, frame = AgentState(_walk_to(sim, chair, 7)[0], 0.0), _blank(sim)
    answer = _ask(oracle, state, frame, "How many chairs are there?").answer
    by_type = Counter(sim.house.room(i.room_id).type for i in sim.house.instances_of("chair"))
    assert answer.startswith("There are ") and " chairs in this house: " in answer
    for room_type, count in by_type.items():
        assert f"{count} in " in answer and room_type in answer
    assert sum(int(word) for word in answer.split() if word.isdigit()) == sum(by_type.values())
    present = {inst.category for inst in sim.house.instances}
    single = sorted(c for c in present if len(sim.house.instances_of(c)) == 1)[0]
    assert _ask(oracle, state, frame, f"how many {single}s are in the house?").answer.startswith(
        f"There is only one {single} in this house, in "
    )
    absent = sorted(name for name in object_names() if " " not in name and name not in present)[0]
    assert _ask(oracle, state, frame, f"How many {absent}s are there?").answer == (
        f"There is no {absent} in this house."
    )


def test_counts_out_of_view_and_by_floor(sim: Simulator, chair: ObjectInstance) -> None:
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, chair)
    state, frame = AgentState(_walk_to(sim, chair, 7)[0], 0.0), _blank(sim)
    assert _ask(oracle, state, frame, "How many chairs are in view?").answer == (
        "No chair is in your view."
    )
    on_floors = _ask(oracle, state, frame, "How many chairs are on this floor?").answer
    assert on_floors.startswith("There are ") and on_floors.endswith("This house has one floor.")


def test_the_neighbourhood_names_the_nearest_objects(sim: Simulator, chair: ObjectInstance) -> None:
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, chair)
    state = AgentState(_walk_to(sim, chair, 8)[0], 0.0)
    answer = _ask(oracle, state, _blank(sim), "What is around it?").answer
    others = sorted(
        (chair.box.distance_to(inst.box), inst.id, inst)
        for inst in sim.house.instances
        if inst.id != chair.id and "ceiling" not in inst.category
    )
    nearest, farthest = others[0][2], others[-1][2]
    room = sim.house.room(chair.room_id).type
    assert answer.startswith(f"It is in the {room}") or answer.startswith(f"It is in this {room}")
    assert nearest.category in answer and farthest.category not in answer


def test_window_answers_follow_the_distance_to_the_window_coverings(sim: Simulator) -> None:
    coverings = [inst for inst in sim.house.instances if inst.category in WINDOW_COVERINGS]
    assert coverings, "the test house needs curtains or blinds"

    def gap(inst: ObjectInstance) -> float:
        return min(inst.box.distance_to(c.box) for c in coverings)

    reachable = [
        inst
        for inst in sim.house.instances
        if inst.category not in WINDOW_COVERINGS and view_points(sim.grid, inst.box)
    ]
    near, far = min(reachable, key=gap), max(reachable, key=gap)
    state = _states(sim, 1, 9)[0]
    frame = _blank(sim)
    by_window = _ask(
        _started(HelpfulOracle(RuleOracle(0)), sim, near), state, frame, "is it near a window?"
    )
    assert by_window.answer.startswith("Yes, it is near a window: ")
    assert by_window.help_kind == "window"
    away = _ask(
        _started(HelpfulOracle(RuleOracle(0)), sim, far), state, frame, "Is it by the window?"
    ).answer
    assert away.startswith(f"No, the nearest window is about {round(gap(far))} meters from it")


# --- settings and records ------------------------------------------------------------------


def test_help_of_a_type_the_run_does_not_allow_is_refused(
    sim: Simulator, chair: ObjectInstance
) -> None:
    oracle = _started(
        HelpfulOracle(RuleOracle(0, question_types=(QuestionType.ATTRIBUTE,))), sim, chair
    )
    state, frame = _states(sim, 1, 10)[0], _blank(sim)
    refused = _ask(oracle, state, frame, "should I go upstairs?")
    assert (refused.answer, refused.type_refused, refused.help_kind) == (
        TYPE_REFUSAL,
        True,
        "floor",
    )
    assert not _ask(oracle, state, frame, "is it near a window?").type_refused


def test_eval_selects_it_and_names_it_in_provenance() -> None:
    config = EvalConfig(agent="random", task="iign", oracle="helpful")
    settings = config.oracle_settings()
    assert settings == OracleSettings(OracleBackend.HELPFUL)
    assert isinstance(settings.make(0), HelpfulOracle)
    provenance = default_provenance(config, None)
    assert (provenance["oracle"], provenance["backend"]) == ("HelpfulOracle", "helpful")
    assert EvalConfig(agent="random", task="iign").oracle_settings().backend_name == "rules"
    worded = EvalConfig(agent="random", task="iign", oracle="helpful", oracle_model="m")
    provenance = default_provenance(worded, None)
    assert (provenance["oracle"], provenance["backend"]) == ("LLMOracle", "openai:m@api.openai.com")
    assert switch_values(worded)["oracle"] == "helpful:m"  # the report's ablation rows
    with pytest.raises(ConfigError, match="rule oracle takes no server"):
        EvalConfig(agent="random", task="iign", oracle_model="m")
    with pytest.raises(ConfigError, match="--oracle-timeout applies to a language model"):
        EvalConfig(agent="random", task="iign", oracle="helpful", oracle_timeout=5.0)


def test_the_environment_gives_the_path_and_records_the_kind_of_help(
    scenes: SceneCache, sim: Simulator, chair: ObjectInstance
) -> None:
    env = _env_with(HelpfulOracle(RuleOracle(1)), scenes, sim, chair, budget=2)
    for _ in range(40):
        action = env.follower.next_action(env.sim.state)
        if action == Action.STOP:
            break
        env.step(action)
    observation, *_ = env.step(Talk("Am I getting closer?"))
    assert observation["oracle_answer"].startswith("Yes, you are getting closer")
    env.step(Talk("What color is it?"))
    record = env.record("test")
    assert [turn.help_kind for turn in record.dialog] == ["closer", "schema"]
    assert [turn.backend for turn in record.dialog] == ["helpful", "helpful"]
    written = record.to_json()
    assert EpisodeRecord.from_json(written) == record
    old = {
        **written,
        "dialog": [{k: v for k, v in t.items() if k != "help_kind"} for t in written["dialog"]],
    }
    assert [turn.help_kind for turn in EpisodeRecord.from_json(old).dialog] == ["", ""]


def test_rule_oracle_records_keep_their_shape(
    scenes: SceneCache, sim: Simulator, chair: ObjectInstance
) -> None:
    env = _env_with(RuleOracle(1), scenes, sim, chair, budget=1)
    env.step(Talk("What color is it?"))
    (turn,) = env.record("test").to_json()["dialog"]
    assert "help_kind" not in turn and turn["backend"] == "rules"


def _env_with(
    oracle: HelpfulOracle | RuleOracle,
    scenes: SceneCache,
    sim: Simulator,
    chair: ObjectInstance,
    budget: int,
) -> NavigationEnv:
    """An IIGN episode for ``chair`` with ``oracle``, started."""
    episode = iign_episode(sim, chair, f"{type(oracle).__name__}-test")
    env = NavigationEnv([episode], TaskConfig(dialog_budget=budget), scenes, oracle)
    env.reset(options={"episode_index": 0})
    return env
