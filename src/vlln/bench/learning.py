"""`vlln bench learning`: the training contract, end to end. A model made from scratch is
trained on a handful of teacher trajectories until it fits them, then plays the same episodes
through the real ``vlln eval --agent vlln`` path.

Steps, all on small houses of the training split (fast to build and to play):

1. ``vlln data build`` of ``houses`` x ``per_house`` IIGN trajectories (the teacher: the
   collector's frontier exploration with dialog);
2. ``vlln data export-sft`` of every decision (``sample_step`` 1 and ``forward_steps``, so
   each frame the model is asked at in closed loop has its teacher's answer);
3. ``vlln train new-model`` of ``size``, then ``vlln train sft`` for ``steps`` steps;
4. the teacher's own score on the kept episodes (its trajectories replayed through the same
   evaluation runner, :class:`vlln.datagen.replay.TrajectoryReplay`), then ``vlln eval
   --agent vlln`` of the trained model on the same episode file.

Figures: ``teacher_success_rate`` and ``overfit_success_rate`` (SR at budget 5, %),
``overfit_ratio`` (the second over the first), ``imitable_share`` (the teacher trajectories
that a model making exactly the exported decisions could finish, if the follower walked each
pixel goal as the teacher did: :func:`vlln.datagen.sft.sampling.imitator_reaches_stop`),
``action_agreement`` (the share of the
teacher's decisions, on the exported prompts, where the model's decoded output is the
teacher's: the same move, turn run, STOP or question, and a pixel goal within
:data:`PIXEL_TOLERANCE` pixels), ``pixel_error_median``, ``prompt_match`` (the share of the
model's calls in evaluation whose prompt, text and image bytes, is one the export trained on:
:func:`prompt_match`) and ``train_seconds``. A model that fits its teacher on the prompts and
then fails in closed loop points at a drift between what training and evaluation show the
model; ``prompt_match`` below 100 % while the model still follows its teacher names it.
"""

from __future__ import annotations

import contextlib
import math
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple

from vlln.bench.figures import Figure, emit
from vlln.bench.settings import AgreementBench, LearningBench
from vlln.datagen.sft.source import SourceTrajectory
from vlln.errors import ConfigError
from vlln.prompt import Conversation, ImageRef, PixelOutput, Turn, prompt_digest, read_output

PIXEL_TOLERANCE = 48.0  # pixels of the 640x480 look-down image: about 0.3 m of floor ahead
_BUDGET = 5


@dataclass(frozen=True)
class Decision:
    """One teacher decision of the export: the prompt's turns, its images and the answer."""

    turns: tuple[Turn, ...]
    images: tuple[Path, ...]
    answer: str


def run_learning_benchmark(settings: LearningBench) -> list[Figure]:
    """Build, train and evaluate in ``settings.out`` (or a temporary folder); print figures."""
    figures: list[Figure] = []

    def note(metric: str, value: float, unit: str) -> None:
        figure = Figure(metric, value, unit)
        figures.append(figure)
        emit(figure, settings.as_json)

    with _work_folder(settings.out) as work:
        outcome = learn(settings, work)
    note("teacher_success_rate", outcome.teacher_sr, "%")
    note("overfit_success_rate", outcome.model_sr, "%")
    note("overfit_ratio", outcome.ratio, "ratio")
    note("action_agreement", outcome.agreement, "%")
    note("pixel_error_median", outcome.pixel_error, "px")
    note("imitable_share", outcome.imitable, "%")
    note("prompt_match", outcome.prompt_match, "%")
    note("episodes", outcome.episodes, "count")
    note("train_samples", outcome.samples, "count")
    note("train_steps", outcome.steps, "steps")
    note("final_loss", outcome.final_loss, "loss")
    note("train_seconds", outcome.train_seconds, "s")
    note("total_seconds", outcome.total_seconds, "s")
    return figures


def run_agreement_benchmark(settings: AgreementBench) -> list[Figure]:
    """:func:`action_agreement` of a model on an export, printed as figures."""
    agreement = action_agreement(settings.model, settings.export, settings.samples)
    figures = [
        Figure("action_agreement", agreement.share, "%"),
        Figure("pixel_error_median", agreement.pixel_error, "px"),
        Figure("decisions", agreement.decisions, "count"),
    ]
    for figure in figures:
        emit(figure, settings.as_json)
    return figures


@dataclass(frozen=True)
class LearningOutcome:
    """What one build-train-evaluate cycle measured."""

    teacher_sr: float
    model_sr: float
    agreement: float
    pixel_error: float
    imitable: float  # % of teacher trajectories an exact imitator of the export finishes
    prompt_match: float  # % of the model's calls in evaluation shown a prompt trained on
    episodes: int
    samples: int
    steps: int
    final_loss: float
    train_seconds: float
    total_seconds: float

    @property
    def ratio(self) -> float:
        return self.model_sr / self.teacher_sr if self.teacher_sr else 0.0


def learn(settings: LearningBench, work: Path) -> LearningOutcome:
    """The whole cycle in ``work`` (module doc); every step resumes what is already there."""
    started = time.perf_counter()
    episode_file, trajectories = _teacher_data(settings, work)
    from vlln.datagen.sft.config import SftConfig
    from vlln.datagen.sft.sampling import imitator_reaches_stop

    sampling = SftConfig(
        sample_step=1,
        min_answers=SftConfig.model_fields["max_answers"].default,  # every answer heard
        history_frames=settings.history,
        forward_steps=True,  # every frame the model stands at has its teacher's decision
        seed=settings.seed,
    )
    imitable = sum(imitator_reaches_stop(t, sampling) for t in trajectories) / len(trajectories)
    export = work / "sft"
    if not (export / "export.json").is_file():
        from vlln.datagen.sft.export import export_sft

        export_sft(work / "data", export, sampling, progress=False)
    model, samples, steps, loss, train_seconds = _train(settings, work, export)
    teacher_sr = _teacher_success(settings, work, episode_file, trajectories)
    model_sr = _model_success(settings, work, episode_file, model)
    agreement, pixel_error, _ = action_agreement(model, export, settings.agreement_samples)
    return LearningOutcome(
        teacher_sr,
        model_sr,
        agreement,
        pixel_error,
        100.0 * imitable,
        prompt_match(work / "eval-model", export).share,
        len(trajectories),
        samples,
        steps,
        loss,
        train_seconds,
        time.perf_counter() - started,
    )


@contextlib.contextmanager
def _work_folder(out: Path | None) -> Iterator[Path]:
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        yield out
        return
    with tempfile.TemporaryDirectory(prefix="vlln-bench-learning-") as folder:
        yield Path(folder)


def _teacher_data(settings: LearningBench, work: Path) -> tuple[Path, list[SourceTrajectory]]:
    """The teacher's trajectories, and an episode file of the episodes they walk."""
    from vlln.datagen.build import BuildConfig, build_dataset
    from vlln.datagen.sft.source import open_houses, read_trajectories
    from vlln.tasks.episode import read_episodes, write_episodes

    config = BuildConfig(
        houses=settings.houses, per_house=settings.per_house, seed=settings.seed, preset="small"
    )
    data = build_dataset(work / "data", config, progress=False)
    trajectories = [t for house in open_houses(data) for t in read_trajectories(house)]
    if not trajectories:
        raise ConfigError("the build kept no trajectory; raise --per-house or --houses")
    kept = {trajectory.episode_key for trajectory in trajectories}
    episodes = read_episodes(data / "episodes" / f"{config.split}_iign.json.gz")
    episode_file = work / "episodes.json.gz"
    write_episodes(episode_file, [e for e in episodes if e.episode_id in kept])
    return episode_file, trajectories


def _train(
    settings: LearningBench, work: Path, export: Path
) -> tuple[Path, int, int, float, float]:
    """A new model of ``settings.size`` trained on ``export``: its folder, samples, steps,
    last logged loss and training seconds."""
    from vlln.train.config import TrainConfig
    from vlln.train.scratch import build_model
    from vlln.train.sft import train_sft

    start = work / "model-new"
    if not (start / "config.json").is_file():
        build_model(start, settings.size, settings.seed)
    config = TrainConfig.build(
        {
            "data_dir": export,
            "model": str(start),
            "out_dir": work / "model",
            "max_steps": settings.steps,
            "batch_size": settings.batch_size,
            "learning_rate": settings.learning_rate,
            "vision_learning_rate": settings.learning_rate,
            "workers": 1,  # images decoded beside the training step (2 cores)
            "save_steps": settings.steps,
            "save_limit": 1,
            "logging_steps": max(1, settings.steps // 20),
            "seed": settings.seed,
        }
    )
    with contextlib.redirect_stdout(sys.stderr):  # the Trainer's log lines are not figures
        outcome = train_sft(config)
    loss = outcome.losses[-1][1] if outcome.losses else math.nan
    return config.out_dir, outcome.samples, outcome.steps, loss, outcome.seconds


def _teacher_success(
    settings: LearningBench, work: Path, episode_file: Path, trajectories: list[SourceTrajectory]
) -> float:
    """SR of the teacher's replayed trajectories, scored by the evaluation runner."""
    from vlln.datagen.replay import TrajectoryReplay
    from vlln.eval.config import EvalConfig
    from vlln.eval.runner import run_evaluation

    config = EvalConfig.build(
        {
            "agent": "teacher",
            "task": "iign",
            "episode_file": str(episode_file),
            "budgets": [_BUDGET],
        }
    )
    replay = TrajectoryReplay(trajectories)
    out = work / "eval-teacher"
    run_evaluation(config, out, progress=False, agent_factory=lambda *_: replay)
    return _success_rate(out)


def _model_success(settings: LearningBench, work: Path, episode_file: Path, model: Path) -> float:
    """SR of the trained model through ``vlln eval --agent vlln``, run as a user runs it."""
    out = work / "eval-model"
    command = [sys.executable, "-m", "vlln.cli", "eval", "--agent", "vlln", "--model", str(model)]
    command += ["--task", "iign", "--episode-file", str(episode_file), "--budgets", str(_BUDGET)]
    command += ["--seed", str(settings.seed), "--out", str(out), "--quiet"]
    finished = subprocess.run(command, stdout=sys.stderr, check=False)
    if finished.returncode != 0:
        raise ConfigError(f"vlln eval of the trained model failed; see {out}")
    return _success_rate(out)


def _success_rate(run: Path) -> float:
    from vlln.eval.results import load_run_records
    from vlln.tasks.metrics import success

    records = load_run_records([run])
    if not records:
        raise ConfigError(f"{run} holds no episode records")
    return 100.0 * sum(success(record) for record in records) / len(records)


class Agreement(NamedTuple):
    share: float  # % of the teacher's decisions the model's decoded output matches
    pixel_error: float  # median pixel distance where both name a pixel goal
    decisions: int  # decisions asked


def action_agreement(model: Path, export: Path, limit: int) -> Agreement:
    """The model's agreement with its teacher over at most ``limit`` decisions spread evenly
    over the export, each asked through the ``vlln`` agent's backend with exactly the
    exported prompt."""
    from vlln.agents.local.backend import ChatRequest, load_backend
    from vlln.train.data import load_rgb

    decisions = teacher_decisions(export)
    chosen = decisions[:: max(1, math.ceil(len(decisions) / limit))]
    backend = load_backend(str(model.resolve()))
    agreed = 0
    errors: list[float] = []
    for decision in chosen:
        conversation = _conversation(decision)
        images = tuple(load_rgb(path) for path in decision.images)
        reply = backend.generate_batch([ChatRequest(conversation, images)])[0]
        look_down = bool(conversation.images) and conversation.images[-1].camera == "down"
        wanted = read_output(decision.answer, look_down=look_down)
        got = read_output(reply.text or "", look_down=look_down)
        if isinstance(wanted, PixelOutput) and isinstance(got, PixelOutput):
            error = math.hypot(got.col - wanted.col, got.row - wanted.row)
            errors.append(error)
            agreed += error <= PIXEL_TOLERANCE
        else:
            agreed += got == wanted
    median = statistics.median(errors) if errors else math.nan
    return Agreement(100.0 * agreed / max(1, len(chosen)), median, len(chosen))


class PromptMatch(NamedTuple):
    share: float  # % of the calls whose prompt is one of the export's decision prompts
    calls: int  # model calls of the run that recorded their prompt's digest


def prompt_match(run: Path, export: Path) -> PromptMatch:
    """How many of the model calls recorded in ``run`` were shown, byte for byte, a prompt
    of one of ``export``'s teacher decisions (:func:`vlln.prompt.prompt_digest` of the turns
    and the image files). A model that follows its teacher in closed loop is shown exactly its
    training prompts, so every call matches; one that does not names a drift in the text
    (connectives, history, dialog) or in the pixels."""
    from vlln.eval.results import load_run_records

    trained = {
        prompt_digest(d.turns, [path.read_bytes() for path in d.images])
        for d in teacher_decisions(export)
    }
    digests = [
        call.prompt_digest
        for record in load_run_records([run])
        for call in record.model_calls
        if call.prompt_digest
    ]
    matched = sum(digest in trained for digest in digests)
    return PromptMatch(100.0 * matched / max(1, len(digests)), len(digests))


def teacher_decisions(export: Path) -> list[Decision]:
    """Every assistant turn of the export with the turns and images before it: one copy of
    each repeated sample, no plain step sample at a frame where the teacher asked first (the
    reference's sampling writes one there, but the teacher's decision was to ask), and no hard
    negative (``--hard-negatives`` repeats decisions at frames of its own choosing), so that
    exports with and without them are scored on the reference's decisions alike."""
    from vlln.train.data import read_export

    samples = read_export(export)
    asked = {_frame_of(sample.sample_id) for sample in samples if "/dialog/" in sample.sample_id}
    decisions: list[Decision] = []
    for sample in samples:
        *_, kind, copy = sample.sample_id.split("/")
        if (
            copy != "0"
            or kind == "negative"
            or (kind == "step" and _frame_of(sample.sample_id) in asked)
        ):
            continue
        for index, turn in enumerate(sample.turns):
            if turn.role != "gpt":
                continue
            before = sample.turns[:index]
            shown = sum(t.text.count("<image>") for t in before)
            decisions.append(Decision(before, sample.images[:shown], turn.text))
    return decisions


def _frame_of(sample_id: str) -> str:
    """``house/episode_i/frame_j`` of a sample id (a mixed export's tag kept)."""
    return sample_id.rsplit("/", 2)[0]


def _conversation(decision: Decision) -> Conversation:
    """The prompt of ``decision``; the export names each image ``<camera>_<frame>.jpg``."""
    refs = []
    for path in decision.images:
        camera, _, frame = path.stem.partition("_")
        refs.append(ImageRef("down" if camera == "down" else "level", int(frame)))
    return Conversation(decision.turns, tuple(refs))
