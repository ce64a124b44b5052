"""The helpful oracle: the paper's rule oracle, and grounded help beyond its questions.

Each question goes first to the recogniser (:mod:`.recognise`). One it does not claim is the
paper's and gets the rule oracle's answer word for word; when that question is "is this the
one?" and several candidates are in view, a clarification follows the answer, in the same
reply and the same turn. One it claims gets an exact answer from the house, the asker's view
and the path it walked. Every reply says which kind of help it gave (``Reply.help_kind``).

The help draws its paraphrases from a generator of its own (seeded by the seed, the house
and the target), so the rule oracle's answers in a dialog do not depend on what else was
asked. A run that allows only some question types refuses help of the others, as the rule
oracle refuses their questions.
"""

from __future__ import annotations

import zlib
from collections.abc import Callable
from dataclasses import replace

import numpy as np

from vlln.errors import ConfigError
from vlln.oracle.helpful.around import answer_neighbourhood, answer_window
from vlln.oracle.helpful.compare import (
    answer_comparison,
    answer_confirmation,
    answer_done,
    clarification,
)
from vlln.oracle.helpful.house import answer_count
from vlln.oracle.helpful.progress import (
    answer_closer,
    answer_floor,
    answer_passed,
    answer_reroute,
)
from vlln.oracle.helpful.recognise import HelpKind, HelpRequest, recognised
from vlln.oracle.helpful.visited import answer_visited
from vlln.oracle.knowledge import EpisodeKnowledge
from vlln.oracle.rule_oracle import TYPE_REFUSAL, RuleOracle
from vlln.oracle.rule_oracle import reads_view as rules_read_view
from vlln.tasks.oracle_protocol import EpisodeContext, Question, QuestionType, Reply

BACKEND = "helpful"
_OWN_STREAM = 1  # keeps the help's generator apart from the rule oracle's

Answerer = Callable[[EpisodeKnowledge, HelpRequest, Question], str]
_ANSWERS: dict[HelpKind, tuple[QuestionType, Answerer]] = {
    HelpKind.COMPARISON: (
        QuestionType.DISAMBIGUATION,
        lambda k, r, q: answer_comparison(k, r, q.state, q.frame),
    ),
    HelpKind.CONFIRMATION: (
        QuestionType.DISAMBIGUATION,
        lambda k, r, q: answer_confirmation(k, r, q.state, q.frame),
    ),
    HelpKind.DONE: (QuestionType.ROUTE, lambda k, r, q: answer_done(k, q.state, q.frame)),
    HelpKind.PASSED: (QuestionType.OTHER, lambda k, r, q: answer_passed(k, q.state, _path(q))),
    HelpKind.CLOSER: (
        QuestionType.OTHER,
        lambda k, r, q: answer_closer(k, q.state, _path(q), yes_no=r.yes_no, reverse=r.reverse),
    ),
    HelpKind.VISITED: (
        QuestionType.OTHER,
        lambda k, r, q: answer_visited(k, r, q.state, _path(q)),
    ),
    HelpKind.FLOOR: (QuestionType.ROUTE, lambda k, r, q: answer_floor(k, r, q.state)),
    HelpKind.REROUTE: (QuestionType.ROUTE, lambda k, r, q: answer_reroute(k, q.state)),
    HelpKind.COUNT: (QuestionType.OTHER, answer_count),
    HelpKind.NEIGHBOURHOOD: (
        QuestionType.ATTRIBUTE,
        lambda k, r, q: answer_neighbourhood(k, q.state, r.relation),
    ),
    HelpKind.WINDOW: (QuestionType.ATTRIBUTE, lambda k, r, q: answer_window(k, q.state)),
    HelpKind.OFF_TOPIC: (QuestionType.OTHER, lambda k, r, q: TYPE_REFUSAL),
}
_READS_VIEW = frozenset({HelpKind.COMPARISON, HelpKind.CONFIRMATION, HelpKind.DONE})


def reads_view(text: str) -> bool:
    """Whether the helpful answer to ``text`` looks at the view it is asked from."""
    request = recognised(text)
    if request is None:
        return rules_read_view(text)
    return request.kind in _READS_VIEW or request.in_view


class HelpfulOracle:
    """The answers of ``rules`` (its seed, question types and cues), and grounded help beyond
    them (module doc)."""

    snapshottable = True  # copy.deepcopy gives an independent oracle (vlln.eval.sweep)

    def __init__(self, rules: RuleOracle) -> None:
        self.rules = rules
        self._knowledge: EpisodeKnowledge | None = None

    def start(self, context: EpisodeContext) -> None:
        self.rules.start(context)
        knowledge = self.rules.knowledge
        house = knowledge.index.house.name.encode("utf-8")
        entropy = [self.rules.seed, zlib.crc32(house), knowledge.target.id, _OWN_STREAM]
        own = np.random.default_rng(np.random.SeedSequence(entropy))
        self._knowledge = replace(knowledge, rng=own)

    def answer(self, question: Question) -> Reply:
        request = recognised(question.text)
        if request is None:
            return self._papers(question)
        if request.kind == HelpKind.OFF_TOPIC:
            papers = self._papers(question)
            if papers.answer == TYPE_REFUSAL:  # the rule oracle refused it already
                return papers
        knowledge = self._started()
        question_type, answerer = _ANSWERS[request.kind]
        kind = request.kind.value
        if question_type not in self.rules.question_types:
            return Reply(TYPE_REFUSAL, question_type, BACKEND, type_refused=True, help_kind=kind)
        return Reply(answerer(knowledge, request, question), question_type, BACKEND, help_kind=kind)

    def _papers(self, question: Question) -> Reply:
        """The rule oracle's reply, with the clarification when it is due."""
        reply = replace(self.rules.answer(question), backend=BACKEND)
        if reply.question_type != QuestionType.DISAMBIGUATION or reply.type_refused:
            return replace(reply, help_kind=HelpKind.SCHEMA.value)
        extra = clarification(self._started(), question.state, question.frame)
        if extra is None:
            return replace(reply, help_kind=HelpKind.SCHEMA.value)
        return replace(
            reply, answer=f"{reply.answer} {extra}", help_kind=HelpKind.CLARIFICATION.value
        )

    def _started(self) -> EpisodeKnowledge:
        if self._knowledge is None:
            raise ConfigError("the oracle has no episode; call start(context) before answer()")
        return self._knowledge


def _path(question: Question) -> tuple[tuple[float, ...], ...]:
    return question.path or (question.state.position,)
