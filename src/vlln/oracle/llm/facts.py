"""The ground-truth facts that fill the paper's answer prompts, computed by the rule oracle's
logic so that a language model only rewords what the house and the agent's state say.

The fields are the prompts' placeholders: goal information (the target's metadata), the
heading to the target, the path description of the next 4 m, the next step of the
shortest-path follower and whether the target is in view.
"""

from __future__ import annotations

from vlln.errors import NavigationError
from vlln.oracle.answers import answer_other, room_phrase
from vlln.oracle.classify import OtherTopic, QuestionAnalysis
from vlln.oracle.knowledge import EpisodeKnowledge, object_phrase
from vlln.oracle.route import answer_path, signed_degrees
from vlln.sim.agent import Action, AgentState
from vlln.sim.renderer import Frame
from vlln.tasks.oracle_protocol import QuestionType

NEARBY_LIMIT = 3  # related objects listed in the goal information
_UNKNOWN = "unknown"
_STEP_WORDS = {
    Action.STOP: "stop, you are there",
    Action.MOVE_FORWARD: "move forward",
    Action.TURN_LEFT: "turn left",
    Action.TURN_RIGHT: "turn right",
}


def goal_information(knowledge: EpisodeKnowledge, state: AgentState) -> str:
    """The target's metadata as "key: value" pairs; unknown values are left out."""
    target = knowledge.target
    attrs = target.attributes
    sx, sy, sz = target.box.size
    pairs = [
        ("category", target.category),
        ("fine category", target.fine_category),
        ("color", attrs.color),
        ("material", attrs.material),
        ("texture", attrs.texture),
        ("shape", attrs.shape),
        ("size", f"{attrs.size} ({max(sx, sz):.1f} m wide, {sy:.1f} m tall)".lstrip()),
        ("placement", attrs.placement),
    ]
    room = knowledge.target_room
    if room is not None:
        pairs.append(("room", room_phrase(knowledge, room, state)))
    index = knowledge.index
    nearby = [
        f"{relation.word} {object_phrase(index.instances[relation.object])}"
        for relation in index.relations.get(target.id, [])[:NEARBY_LIMIT]
    ]
    pairs.append(("nearby objects", ", ".join(nearby)))
    pairs.append(("caption", target.caption))
    return "; ".join(f"{key}: {value}" for key, value in pairs if value)


def heading(knowledge: EpisodeKnowledge, state: AgentState) -> str:
    """The turn from the agent's heading to the straight line to the target."""
    angle = round(signed_degrees(knowledge, state) / 10.0) * 10
    if angle == 0:
        return "straight ahead"
    if abs(angle) >= 170:
        return "behind the agent (turn around)"
    return f"turn {'left' if angle > 0 else 'right'} about {abs(angle)} degrees"


def next_step(knowledge: EpisodeKnowledge, state: AgentState) -> str:
    """The shortest-path follower's next action, in words."""
    try:
        return _STEP_WORDS[knowledge.follower.next_action(state)]
    except NavigationError:
        return _UNKNOWN


def target_detected(knowledge: EpisodeKnowledge, state: AgentState, frame: Frame) -> str:
    """Whether, and where, the target is in the agent's current view."""
    analysis = QuestionAnalysis("", QuestionType.OTHER, other=OtherTopic.VISIBILITY)
    return answer_other(knowledge, analysis, state, frame)


def route_facts(knowledge: EpisodeKnowledge, state: AgentState) -> dict[str, str]:
    """The placeholders of the Route prompt."""
    return {
        "heading": heading(knowledge, state),
        "path_description": answer_path(knowledge, state),
        "next_step": next_step(knowledge, state),
    }


def all_facts(knowledge: EpisodeKnowledge, state: AgentState, frame: Frame) -> dict[str, str]:
    """The placeholders of the Other prompt: every fact the oracle has."""
    return {
        "goal_information": goal_information(knowledge, state),
        **route_facts(knowledge, state),
        "target_detected": target_detected(knowledge, state, frame),
    }
