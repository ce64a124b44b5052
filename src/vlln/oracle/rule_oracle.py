"""The default oracle: offline, deterministic, grounded in the house and the agent's state.

It classifies each question with :func:`vlln.oracle.classify.analysed` and answers
with the logic of its type (paper supplementary, docs/reference-facts.md §4), without a language
model, a network or model weights. Everything an answer needs (the geodesic field to the
target's view points, the shortest-path follower, per-house look-ups) is built in
:meth:`RuleOracle.start`, so answers are look-ups.

Wording varies between paraphrases drawn from a generator seeded by the oracle's seed, the
house and the target, so the same seed and episode give the same words, byte for byte. The
dialog budget is not the oracle's business: the environment refuses questions past it.
"""

from __future__ import annotations

from vlln.errors import ConfigError
from vlln.oracle.answers import answer_attribute, answer_other
from vlln.oracle.classifier.model import packaged_classifier
from vlln.oracle.classify import OtherTopic, RouteKind, analysed
from vlln.oracle.disambiguation import answer_disambiguation
from vlln.oracle.knowledge import EpisodeKnowledge, HouseIndex
from vlln.oracle.route import CANNOT_ANSWER, answer_orientation, answer_path, answer_step
from vlln.tasks.oracle_protocol import EpisodeContext, Question, QuestionType, Reply

ALL_QUESTION_TYPES: tuple[QuestionType, ...] = tuple(QuestionType)

TYPE_REFUSAL = CANNOT_ANSWER
"""The answer to a question of a type the run does not allow. The paper gives no wording for
its question-type ablation; this is its oracle's default answer to a question it cannot
answer ("Sorry, I cannot answer your question now.", paper supplementary, NPC logic "Other")."""


def reads_view(text: str) -> bool:
    """Whether the answer to this question looks at the view it is asked from: only
    disambiguation ("is this the one?") and visibility ("can I see it?") answers do. A caller
    that must render the view itself, as the oracle service does, can skip the others."""
    analysis = analysed(text)
    return (
        analysis.question_type == QuestionType.DISAMBIGUATION
        or analysis.other == OtherTopic.VISIBILITY
    )


class RuleOracle:
    """Answers Attribute, Route, Disambiguation and Other questions by rules.

    ``seed`` picks the paraphrases; ``goal_radius`` is where the follower says "you are
    there" (the benchmark's 0.25 m success radius). A question of a type not in
    ``question_types`` gets :data:`TYPE_REFUSAL` (its turn is still spent); ``cues`` lets a
    disambiguation "no" say how the target differs (False: yes or no only, the paper's).
    """

    snapshottable = True  # copy.deepcopy gives an independent oracle (vlln.eval.sweep)

    def __init__(
        self,
        seed: int = 0,
        goal_radius: float = 0.25,
        *,
        question_types: tuple[QuestionType, ...] = ALL_QUESTION_TYPES,
        cues: bool = False,
    ) -> None:
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
            raise ConfigError(f"seed must be a whole number >= 0, got {seed!r}")
        if not goal_radius > 0.0:
            raise ConfigError(f"goal_radius must be positive metres, got {goal_radius!r}")
        self.seed = seed
        self.goal_radius = float(goal_radius)
        self.question_types = frozenset(question_types)
        self.cues = cues
        self._index: HouseIndex | None = None
        # Load the question classifier now (once per process), not at the first question,
        # whose answer would otherwise wait a second or two for it.
        packaged_classifier()
        self._knowledge: EpisodeKnowledge | None = None

    def start(self, context: EpisodeContext) -> None:
        """Prepare an episode: look-ups for its house, the field and follower to its goals."""
        if not context.view_points:
            raise ConfigError(
                f"the episode's target {context.target.id} ({context.target.category}) has no "
                "view points; the oracle needs at least one to give route answers"
            )
        simulator = context.simulator
        house = simulator.house
        if self._index is None or self._index.house is not house:
            self._index = HouseIndex.build(house)
        self._knowledge = EpisodeKnowledge.for_episode(
            context, self._index, self.seed, self.goal_radius
        )

    @property
    def knowledge(self) -> EpisodeKnowledge:
        """The episode's look-ups, for answerers built on this oracle."""
        if self._knowledge is None:
            raise ConfigError("the oracle has no episode; call start(context) before answer()")
        return self._knowledge

    def answer(self, question: Question) -> Reply:
        """The answer to one question, with the type it was classified as."""
        knowledge = self.knowledge
        analysis = analysed(question.text)
        state = question.state
        kind = analysis.question_type
        if kind not in self.question_types:
            return Reply(TYPE_REFUSAL, kind, type_refused=True)
        if kind == QuestionType.ATTRIBUTE:
            text = answer_attribute(knowledge, analysis, state)
        elif kind == QuestionType.DISAMBIGUATION:
            text = answer_disambiguation(knowledge, state, question.frame, self.cues)
        elif kind == QuestionType.ROUTE:
            if analysis.route_kind == RouteKind.ORIENTATION:
                text = answer_orientation(knowledge, state)
            elif analysis.route_kind == RouteKind.STEP:
                text = answer_step(knowledge, analysis, state)
            else:
                text = answer_path(knowledge, state)
        else:
            text = answer_other(knowledge, analysis, state, question.frame)
        return Reply(text, kind)
