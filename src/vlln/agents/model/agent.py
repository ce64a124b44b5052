"""The model-agent loop: any vision-language model driving the benchmark's agent.

Each decision builds the shared prompt (:func:`vlln.prompt.build_conversation`) from the
episode's level frames and dialog, asks the model (:class:`VisionLanguageModel`), reads the
reply (:func:`vlln.prompt.read_output`) and turns it into environment actions:

* ``<talk>q`` -> ``Talk(q)``; the oracle's answer joins the dialog at the current frame, so the
  next prompt carries the question and answer as the reference does (assistant ``<talk>`` turn,
  then the answer as a human turn), and later prompts carry them in the history.
* ``<move>←←`` -> that many TURN actions, played one per step without asking again.
* ``<move>↓`` -> LOOK_DOWN, then a second call in the same conversation showing the look-down
  frame (:func:`vlln.prompt.with_look_down`); ``<move>col row`` there -> ``PixelGoal`` and up to
  :data:`MAX_FOLLOW_STEPS` steps of the environment's waypoint follower before the next call.
* ``<move>↑`` -> FORWARD, ``<move>STOP`` -> STOP (after a LOOK_UP when the camera is tilted).
* An unreadable reply -> ``FailedOutput("parse")``; no reply -> ``FailedOutput("server")``.
  Both waste one step and the environment levels the camera; neither is ever a move or a STOP.

Every call's raw output is kept (:meth:`ModelAgent.model_calls`) for the episode record, up to
:data:`~vlln.tasks.record.MAX_STORED_OUTPUT_CHARS` characters (the cut is counted in the call).
"""

from __future__ import annotations

from collections import deque

from vlln.agents.model.backend import ModelReply, VisionLanguageModel
from vlln.prompt import (
    DEFAULT_HISTORY_COUNT,
    Conversation,
    DialogExchange,
    ForwardOutput,
    ParseFailure,
    PixelOutput,
    StopOutput,
    TalkOutput,
    TiltDownOutput,
    TurnOutput,
    build_conversation,
    connective_for,
    prompt_digest,
    read_output,
    with_look_down,
    with_reply,
)
from vlln.prompt.images import model_image
from vlln.sim.agent import Action
from vlln.tasks.env import EpisodeInfo, Observation
from vlln.tasks.record import MAX_STORED_OUTPUT_CHARS, ModelCall
from vlln.tasks.spec import AgentOutput, FailedOutput, PixelGoal, Talk

MAX_FOLLOW_STEPS = 8  # follower steps toward a pixel goal before the model is asked again
_MOVES = (Action.MOVE_FORWARD, Action.TURN_LEFT, Action.TURN_RIGHT)
_COUNTED = (*_MOVES, Action.STOP)


class ModelAgent:
    """Plays an episode by asking ``model`` at every decision (module doc)."""

    privileged = False

    def __init__(
        self,
        model: VisionLanguageModel,
        seed: int,
        name: str = "model",
        history_count: int = DEFAULT_HISTORY_COUNT,
    ) -> None:
        self.model = model
        self.seed = int(seed)
        self.name = name
        self.history_count = history_count
        self._episode: EpisodeInfo | None = None

    def reset(self, episode: EpisodeInfo) -> None:
        self._episode = episode
        self._frames: list[bytes] = []  # level frames as the model sees them
        self._down: bytes | None = None  # the look-down frame of the current frame
        self._dialogs: list[DialogExchange] = []
        self._queue: deque[AgentOutput] = deque()
        self._question: str | None = None  # asked, answer not yet heard
        self._looking_down: Conversation | None = None  # awaiting the look-down frame
        self._follow_left = 0
        self._last: AgentOutput | None = None
        self._steps = 0
        self._calls: list[ModelCall] = []

    def model_calls(self) -> list[ModelCall]:
        """Every call of this episode: raw output or error, latency and tokens."""
        return list(self._calls)

    def act(self, observation: Observation) -> AgentOutput:
        output = self._next(observation)
        self._last = output
        if isinstance(output, Talk):
            self._question = output.text
        if isinstance(output, FailedOutput) or output in _COUNTED:
            self._steps += 1
        return output

    # ------------------------------------------------------------------ the loop
    def _next(self, observation: Observation) -> AgentOutput:
        self._see(observation)
        if self._question is not None:
            answer = observation.get("oracle_answer") or ""
            self._dialogs.append(DialogExchange(self._frame, self._question, str(answer)))
            self._question = None
            return self._decide(self._conversation(), observation)
        if self._looking_down is not None:
            self._down = model_image(observation["rgb"], "down")
            episode = self._require_episode()
            connective = connective_for(self.seed, episode.episode_id, self._frame, look_down=True)
            shown = with_look_down(self._looking_down, self._frame, connective=connective)
            self._looking_down = None
            return self._decide(shown, observation)
        if self._queue:
            return self._queue.popleft()
        waypoint_action = observation.get("waypoint_action")
        if self._follow_left > 0 and isinstance(waypoint_action, Action):
            self._follow_left -= 1
            return waypoint_action
        self._follow_left = 0
        return self._decide(self._conversation(), observation)

    def _see(self, observation: Observation) -> None:
        """Keep a new level frame: the first one, and each after a move."""
        first = not self._frames
        if _level(observation) and (first or self._last in _MOVES):
            self._frames.append(model_image(observation["rgb"], "level"))
            self._down = None

    @property
    def _frame(self) -> int:
        return len(self._frames) - 1

    def _conversation(self) -> Conversation:
        episode = self._require_episode()
        return build_conversation(
            episode.instruction,
            self._frame,
            self._dialogs,
            connective=connective_for(self.seed, episode.episode_id, self._frame),
            dialog_enabled=episode.dialog_budget > 0,
            history_count=self.history_count,
        )

    def _decide(self, conversation: Conversation, observation: Observation) -> AgentOutput:
        images = [
            self._frames[ref.frame] if ref.camera == "level" else self._require_down()
            for ref in conversation.images
        ]
        look_down = conversation.images[-1].camera == "down"
        reply = self.model.generate(conversation, images)
        self._record(reply, look_down, prompt_digest(conversation.turns, images))
        if reply.text is None:
            return FailedOutput("server", reply.error or "no reply")
        output = read_output(reply.text, look_down=look_down)
        tilted = not _level(observation)
        if isinstance(output, ParseFailure):
            return FailedOutput("parse", output.reason)
        if isinstance(output, TalkOutput):
            if self._require_episode().dialog_budget == 0:
                return FailedOutput("parse", "a question, but dialog is disabled")
            return self._levelled([Talk(output.question)], tilted)
        if isinstance(output, TiltDownOutput):
            if tilted:
                return FailedOutput("parse", "tilt down while already looking down")
            self._looking_down = with_reply(conversation, output)
            return Action.LOOK_DOWN
        if isinstance(output, PixelOutput):
            self._follow_left = MAX_FOLLOW_STEPS
            return PixelGoal(output.col, output.row)
        return self._levelled(self._actions_for(output), tilted)

    def _levelled(self, actions: list[AgentOutput], tilted: bool) -> AgentOutput:
        """Play ``actions`` from the next step on, after a LOOK_UP if the camera is tilted."""
        if tilted:
            actions.insert(0, Action.LOOK_UP)
        self._queue.extend(actions[1:])
        return actions[0]

    @staticmethod
    def _actions_for(output: TurnOutput | ForwardOutput | StopOutput) -> list[AgentOutput]:
        if isinstance(output, TurnOutput):
            return [output.action] * output.count
        return [Action.MOVE_FORWARD if isinstance(output, ForwardOutput) else Action.STOP]

    def _record(self, reply: ModelReply, look_down: bool, digest: str) -> None:
        text = reply.text
        cut = 0 if text is None else max(0, len(text) - MAX_STORED_OUTPUT_CHARS)
        self._calls.append(
            ModelCall(
                step=self._steps,
                text=None if text is None else text[:MAX_STORED_OUTPUT_CHARS],
                error=reply.error,
                look_down=look_down,
                latency_ms=round(reply.latency_ms, 3),
                prompt_tokens=reply.prompt_tokens,
                completion_tokens=reply.completion_tokens,
                truncated_chars=cut,
                prompt_digest=digest,
            )
        )

    def _require_down(self) -> bytes:
        if self._down is None:
            raise RuntimeError("the prompt shows a look-down image that was never taken")
        return self._down

    def _require_episode(self) -> EpisodeInfo:
        if self._episode is None:
            raise RuntimeError("reset() the agent before act()")
        return self._episode


def _level(observation: Observation) -> bool:
    return abs(float(observation["tilt"])) < 1e-6
