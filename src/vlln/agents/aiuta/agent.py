"""The AIUTA-style baseline: VLFM-style exploration, and a self-dialogue at every candidate.

It explores as the VLFM-style agent does (:mod:`vlln.agents.vlfm`; AIUTA runs on VLFM) and
sees objects through the same detector. When an object the detector takes for the target
category is in the middle of its view, it runs AIUTA's Self-Questioner and Interaction
Trigger (:mod:`.prompts`) with a vision-language model behind an OpenAI-compatible server:
the trigger's score makes it stop at the object, explore on, or ask the oracle the question
the model proposes; an answer joins the facts about the target and the trigger runs again.

Every model call is kept for the episode record. A call the server does not answer is a
``FailedOutput("server")`` and a reply without a score a ``FailedOutput("parse")``: a wasted,
counted step, never a move; the object is examined again at the next step.
"""

from __future__ import annotations

from typing import Self

import numpy as np
from numpy.typing import NDArray
from pydantic import Field, model_validator

from vlln.agents.aiuta import prompts
from vlln.agents.frontier import dialog
from vlln.agents.frontier.detector import Candidate
from vlln.agents.frontier.mapping import Pose
from vlln.agents.model.openai_vlm import jpeg_data_url
from vlln.agents.vlfm import VlfmAgent
from vlln.config import settings_dataclass
from vlln.errors import ConfigError
from vlln.oracle.llm.openai_client import OpenAIChatClient
from vlln.oracle.llm.protocol import ImagePart, LanguageModelError, Message, TextPart
from vlln.prompt.images import model_image
from vlln.tasks.env import EpisodeInfo, Observation
from vlln.tasks.record import MAX_STORED_OUTPUT_CHARS, ModelCall
from vlln.tasks.spec import AgentOutput, FailedOutput, TaskType


@settings_dataclass
class AiutaSettings:
    """The self-dialogue's knobs (AIUTA's thresholds on a 0-10 alignment score)."""

    self_questions: int = Field(default=3, ge=0)
    """questions the Self-Questioner asks itself per object"""
    stop_score: float = Field(default=8.0, le=10.0)  # at or above: this is the target, stop at it
    skip_score: float = Field(default=4.0, ge=0.0)  # below: not the target, explore on
    max_tokens: int = 256
    temperature: float = 0.0

    @model_validator(mode="after")
    def _skip_below_stop(self) -> Self:
        if not self.skip_score <= self.stop_score:
            raise ConfigError(
                f"need skip_score <= stop_score, got {self.skip_score}, {self.stop_score}"
            )
        return self


class _CallFailed(Exception):
    """A model call that gave no usable reply; the step becomes this failed output."""

    def __init__(self, output: FailedOutput) -> None:
        super().__init__(output.detail)
        self.output = output


class AiutaAgent(VlfmAgent):
    """VLFM-style explorer with AIUTA's self-dialogue and interaction trigger (module doc)."""

    snapshottable = False  # it holds a live HTTP client; budgets are played one by one

    def __init__(
        self,
        client: OpenAIChatClient,
        seed: int = 0,
        detector: str = "truth",
        settings: AiutaSettings | None = None,
    ) -> None:
        super().__init__(seed, detector=detector)
        self.name = "aiuta"
        self.client = client
        self.settings = settings or AiutaSettings()
        self._calls: list[ModelCall] = []

    def reset(self, episode: EpisodeInfo) -> None:
        super().reset(episode)
        self.known = {}  # what fits the target is the model's call, not the detector's
        self.facts = [episode.instruction]
        self.observed: dict[int, str] = {}  # refined description per examined object
        self._calls = []
        self._rgb: NDArray[np.uint8] | None = None
        self._budget_left = 0

    def model_calls(self) -> list[ModelCall]:
        return list(self._calls)

    def act(self, observation: Observation) -> AgentOutput:
        self._rgb = observation["rgb"]
        self._budget_left = int(observation.get("questions_left") or 0)
        return super().act(observation)

    # ----------------------------------------------------------------- the self-dialogue
    def _needs_confirmation(self, candidate: Candidate) -> bool:
        return candidate.instance_id != self.confirmed

    def _inspect(self, candidate: Candidate) -> AgentOutput | None:
        key = candidate.instance_id
        try:
            if key not in self.observed:
                self.observed[key] = self._self_question()
            verdict = prompts.read_verdict(self._ask_model(self._trigger_prompt(key)))
        except _CallFailed as failed:
            return failed.output
        if verdict is None:
            return FailedOutput("parse", "the interaction trigger gave no score from 0 to 10")
        cfg = self.settings
        may_ask = self._may_ask() and verdict.question is not None
        if verdict.score >= cfg.stop_score or (
            not may_ask and verdict.score >= (cfg.stop_score + cfg.skip_score) / 2.0
        ):
            self.confirmed = key
            return None
        if verdict.score < cfg.skip_score or not may_ask or verdict.question is None:
            self.rejected.add(key)
            return None
        return self._ask("aiuta", verdict.question, key)

    def _self_question(self) -> str:
        """Self-Questioner: describe, question the description, keep what is sure, rewrite."""
        category = self.episode.object_category
        description = self._ask_model(prompts.describe(category), image=True)
        count = self.settings.self_questions
        if count == 0:
            return description
        listed = self._ask_model(prompts.self_questions(category, description, count))
        checks = []
        for question in prompts.read_questions(listed, count):
            reply = self._ask_model(prompts.answer(category, question), image=True)
            if not prompts.is_unsure(reply):
                checks.append((question, reply.strip()))
        return self._ask_model(prompts.refine(category, description, checks)).strip()

    def _trigger_prompt(self, key: int) -> str:
        return prompts.trigger(self.episode.object_category, self.facts, self.observed[key])

    def _may_ask(self) -> bool:
        info = self.episode
        talks = info.task != TaskType.OBJECTNAV and info.dialog_budget > 0
        return talks and not self._dialog_closed and self._budget_left > 0

    def _read_answer(self, kind: str, about: int | None, answer: str, pose: Pose) -> None:
        """An answer joins the facts about the target; the trigger runs again on the object
        at the next step. A refusal closes the dialog."""
        self._aim = None
        self._trail.clear()
        if dialog.is_refusal(answer):
            self._dialog_closed = True
        elif answer.strip() and not prompts.is_unsure(answer):
            self.facts.append(f"The user said: {answer.strip()}")

    # ----------------------------------------------------------------- model calls
    def _ask_model(self, text: str, image: bool = False) -> str:
        """One call: ``text`` (after the current view when ``image``); the reply's text."""
        content: str | tuple[ImagePart, TextPart] = text
        if image:
            if self._rgb is None:
                raise RuntimeError("act() before asking about the view")
            picture = jpeg_data_url(model_image(self._rgb, "level"))
            content = (ImagePart(picture), TextPart(text))
        cfg = self.settings
        try:
            completion = self.client.complete(
                [Message("user", content)], max_tokens=cfg.max_tokens, temperature=cfg.temperature
            )
        except LanguageModelError as error:
            self._record(None, str(error)[:500], error.latency_ms)
            raise _CallFailed(FailedOutput("server", str(error)[:200] or "no reply")) from None
        usage = completion.usage
        self._record(
            completion.text,
            None,
            completion.latency_ms,
            usage.prompt_tokens,
            usage.completion_tokens,
        )
        return completion.text

    def _record(
        self,
        text: str | None,
        error: str | None,
        latency_ms: float,
        prompt_tokens: int = 0,
        completion_tokens: int = 0,
    ) -> None:
        cut = 0 if text is None else max(0, len(text) - MAX_STORED_OUTPUT_CHARS)
        self._calls.append(
            ModelCall(
                step=self._steps,
                text=None if text is None else text[:MAX_STORED_OUTPUT_CHARS],
                error=error,
                look_down=False,
                latency_ms=round(latency_ms, 3),
                prompt_tokens=prompt_tokens,
                completion_tokens=completion_tokens,
                truncated_chars=cut,
            )
        )
