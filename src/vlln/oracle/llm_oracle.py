"""The paper's oracle with a language model: the model classifies and words, rules ground.

Per question the model is called at most twice: once with the paper's prompt 1 to classify
it, and once with prompt 2, 3 or 4 to word the answer from ground-truth facts that the rule
oracle's logic computes (the target's metadata, the heading, the next 4 m of path, the next
step, whether the target is in view), together with the rule oracle's own answer to reword.
Disambiguation stays deterministic and needs no second call, as in the paper. The rule
oracle's settings hold here too: a question the model classifies as a type the rule oracle
does not allow gets its refusal, without a second call; disambiguation gives cues only when
the rule oracle does.

Failures never stop an episode: a classification reply that names no type is replaced by the
offline classifier's type, and a call that fails after the client's retries is replaced by
the rule oracle's answer (when the server cannot be reached at all, the second call is not
tried); the reply then says ``fallback=True``. With ``helpful``, the helpful oracle grounds
instead of the rule oracle: a question it claims beyond the paper's schema gets one call, the
help prompt with its answer to reword (docs/helpful-oracle.md). With the
:class:`~vlln.oracle.llm.offline.OfflineLanguageModel` the answers are the rule oracle's, word
for word.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, replace

from vlln.errors import ConfigError
from vlln.oracle.disambiguation import answer_disambiguation
from vlln.oracle.helpful.oracle import HelpfulOracle
from vlln.oracle.helpful.recognise import HelpKind
from vlln.oracle.knowledge import EpisodeKnowledge, HouseIndex
from vlln.oracle.llm.facts import all_facts, goal_information, route_facts, target_detected
from vlln.oracle.llm.prompts import (
    ATTRIBUTE_PROMPT,
    HELP_PROMPT,
    OTHER_PROMPT,
    ROUTE_PROMPT,
    answer_messages,
    classification_messages,
    parse_question_type,
    strip_thinking,
)
from vlln.oracle.llm.protocol import (
    Completion,
    LanguageModel,
    LanguageModelError,
    LanguageModelUnavailableError,
    Message,
)
from vlln.oracle.rule_oracle import TYPE_REFUSAL, RuleOracle
from vlln.tasks.oracle_protocol import EpisodeContext, Question, QuestionType, Reply

logger = logging.getLogger(__name__)

# Help kinds answered through the paper's prompts ("" from the rule oracle).
_THE_PAPERS = frozenset({"", HelpKind.SCHEMA.value, HelpKind.CLARIFICATION.value})


@dataclass
class _Spend:
    """What the model calls for one question cost, and whether offline logic stood in."""

    latency_ms: float = 0.0
    prompt_tokens: int = 0
    completion_tokens: int = 0
    fallback: bool = False
    unavailable: bool = False  # a call failed for want of a server, not for a bad reply

    def add(self, completion: Completion) -> None:
        self.latency_ms += completion.latency_ms
        self.prompt_tokens += completion.usage.prompt_tokens
        self.completion_tokens += completion.usage.completion_tokens

    def failed(self, error: LanguageModelError) -> None:
        self.latency_ms += error.latency_ms
        self.fallback = True
        self.unavailable |= isinstance(error, LanguageModelUnavailableError)


class LLMOracle:
    """An :class:`~vlln.tasks.oracle_protocol.Oracle` that asks ``model`` to classify and word.

    ``fallback`` is the rule oracle that grounds every answer and stands in for failed calls
    (default: ``RuleOracle(seed)``); ``seed`` must match its seed when both are given.
    """

    def __init__(
        self,
        model: LanguageModel,
        seed: int = 0,
        fallback: RuleOracle | None = None,
        *,
        max_tokens: int = 256,
        temperature: float = 0.0,
        helpful: bool = False,
    ) -> None:
        if fallback is None:
            fallback = RuleOracle(seed)
        elif fallback.seed != seed:
            raise ConfigError(
                f"seed {seed!r} differs from the fallback oracle's seed {fallback.seed!r}; "
                "pass the same seed or leave fallback out"
            )
        if isinstance(max_tokens, bool) or not isinstance(max_tokens, int) or max_tokens < 1:
            raise ConfigError(f"max_tokens must be a whole number >= 1, got {max_tokens!r}")
        if not 0.0 <= temperature <= 2.0:
            raise ConfigError(f"temperature must be in [0, 2], got {temperature!r}")
        self.model = model
        self.seed = seed
        self.fallback = fallback
        self.max_tokens = max_tokens
        self.temperature = float(temperature)
        self._grounds: RuleOracle | HelpfulOracle = HelpfulOracle(fallback) if helpful else fallback
        self._index: HouseIndex | None = None
        self._knowledge: EpisodeKnowledge | None = None

    def start(self, context: EpisodeContext) -> None:
        """Start the rule oracle's episode and the look-ups that the prompts' facts read."""
        self._grounds.start(context)
        simulator = context.simulator
        house = simulator.house
        if self._index is None or self._index.house is not house:
            self._index = HouseIndex.build(house)
        self._knowledge = EpisodeKnowledge.for_episode(
            context, self._index, self.seed, self.fallback.goal_radius
        )

    def answer(self, question: Question) -> Reply:
        """Classify with the model, answer from the facts, fall back where a call fails."""
        knowledge = self._knowledge
        if knowledge is None:
            raise ConfigError("the oracle has no episode; call start(context) before answer()")
        offline = self._grounds.answer(question)
        if offline.help_kind not in _THE_PAPERS:
            return self._help(knowledge, question, offline)
        spend = _Spend()
        kind = self._classify(question.text, offline.question_type, spend)
        refused = False
        if spend.unavailable:  # the server is down: do not wait out its retries twice
            kind, text, refused = offline.question_type, offline.answer, offline.type_refused
        elif kind not in self.fallback.question_types:
            text, refused = TYPE_REFUSAL, True
        elif kind == QuestionType.DISAMBIGUATION:
            if offline.question_type == kind:
                text = offline.answer
            else:
                cues = self.fallback.cues
                text = answer_disambiguation(knowledge, question.state, question.frame, cues)
        else:
            reference = offline.answer if offline.question_type == kind else None
            messages = _answer_messages(knowledge, kind, question, reference)
            worded = self._call(messages, spend)
            if worded is None:
                kind, text, refused = offline.question_type, offline.answer, offline.type_refused
            else:
                text = worded
        return Reply(
            text,
            kind,
            backend=self.model.backend,
            latency_ms=round(spend.latency_ms, 3),
            prompt_tokens=spend.prompt_tokens,
            completion_tokens=spend.completion_tokens,
            fallback=spend.fallback,
            type_refused=refused,
            help_kind=offline.help_kind,
        )

    def _help(self, knowledge: EpisodeKnowledge, question: Question, offline: Reply) -> Reply:
        """Help beyond the paper's schema: the helpful oracle's answer, reworded in one call
        (its refusal of a type the run does not answer or of a question about nothing in the
        house, as it is: the paper's words, and nothing for a model to answer instead)."""
        if offline.type_refused or offline.help_kind == HelpKind.OFF_TOPIC.value:
            return replace(offline, backend=self.model.backend)
        facts = {
            "goal_information": goal_information(knowledge, question.state),
            "target_detected": target_detected(knowledge, question.state, question.frame),
            "help_kind": offline.help_kind,
        }
        spend = _Spend()
        messages = answer_messages(HELP_PROMPT, facts, question.text, offline.answer)
        worded = self._call(messages, spend)
        return replace(
            offline,
            answer=offline.answer if worded is None else worded,
            backend=self.model.backend,
            latency_ms=round(spend.latency_ms, 3),
            prompt_tokens=spend.prompt_tokens,
            completion_tokens=spend.completion_tokens,
            fallback=spend.fallback,
        )

    def _classify(self, text: str, offline: QuestionType, spend: _Spend) -> QuestionType:
        reply = self._call(classification_messages(text), spend)
        if reply is None:
            return offline
        kind = parse_question_type(reply)
        if kind is None:
            logger.warning(
                "%s named no question type (%r); using the offline classifier's %s",
                self.model.backend,
                reply[:80],
                offline.value,
            )
            spend.fallback = True
            return offline
        return kind

    def _call(self, messages: list[Message], spend: _Spend) -> str | None:
        """The model's text, or None when the call failed (the failure is logged)."""
        try:
            completion = self.model.complete(
                messages, max_tokens=self.max_tokens, temperature=self.temperature
            )
        except LanguageModelError as error:
            logger.warning("%s failed, answering offline: %s", self.model.backend, error)
            spend.failed(error)
            return None
        spend.add(completion)
        text = strip_thinking(completion.text)
        if not text:
            logger.warning("%s answered an empty text, answering offline", self.model.backend)
            spend.fallback = True
            return None
        return text


def _answer_messages(
    knowledge: EpisodeKnowledge, kind: QuestionType, question: Question, reference: str | None
) -> list[Message]:
    """Prompt 2 (Attribute), 3 (Route) or 4 (Other) with the facts it asks for."""
    state = question.state
    if kind == QuestionType.ATTRIBUTE:
        facts = {"goal_information": goal_information(knowledge, state)}
        return answer_messages(ATTRIBUTE_PROMPT, facts, question.text, reference)
    if kind == QuestionType.ROUTE:
        facts = route_facts(knowledge, state)
        return answer_messages(ROUTE_PROMPT, facts, question.text, reference)
    facts = all_facts(knowledge, state, question.frame)
    return answer_messages(OTHER_PROMPT, facts, question.text, reference)
