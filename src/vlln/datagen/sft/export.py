"""``vlln data export-sft``: a trajectory dataset as multi-image conversations for training.

::

    <out>/sft.jsonl        one sample per line, in house, episode and sample order
                           (the line's schema: :mod:`vlln.datagen.sft.records`)
    <out>/images/<house>/episode_<i>/{level,down}_<frame>.jpg   level 384x384, down 640x480
    <out>/export.json      format, settings, houses (and their preset) and counts; written
                           last, so its presence marks a complete export

Several datasets (say one per task, as the paper co-trains on IIGN, IGN and ObjectNav) are
mixed into one export: each is given a tag (its task, from its ``build.json``; numbered where
two share a task), its images go under ``images/<tag>/`` and its sample ids start with
``<tag>/``, and ``export.json`` adds ``datasets`` (each one's tag, folder, task, strategy,
preset, houses and counts) and ``counts_by_task``. ``preset`` names the houses the
trajectories were walked in (``mixed`` when the datasets' differ), so a model trained on the
export can say which houses it knows. Samples are written dataset after dataset; the
trainer draws them in random order. One dataset exports as it always did, without tags.

Which frames become samples is the reference's sampling (:mod:`vlln.datagen.sft.sampling`);
the text of every sample is made by :mod:`vlln.prompt`, the functions the model agents call,
so a sample is exactly what an agent would send in the same state. Random choices (the answers
left before the question limit, the connectives) come from the seed only: the same dataset and
settings give the same bytes. The connectives are drawn from the seed a model agent gets in
``vlln eval`` with the same ``--seed`` for the same episode (:func:`agent_seed`), so a sample
is what the agent sends, not merely drawn alike. Images are written plainly, ``sft.jsonl``
through a temporary file and a rename, and ``export.json`` (removed first when an earlier
export is overwritten) atomically at the end: a killed export leaves a folder without
``export.json`` that a rerun overwrites.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
import zlib
from collections import Counter
from collections.abc import Callable, Iterator, Sequence
from contextlib import closing, contextmanager, suppress
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import IO, Any

import numpy as np
from tqdm import tqdm

from vlln import __version__
from vlln.datagen.build import Strategy, recorded_strategy
from vlln.datagen.reader import HouseDataset
from vlln.datagen.sft.config import SftConfig
from vlln.datagen.sft.distractors import DISTRACTOR_TASKS, DistractorViews
from vlln.datagen.sft.images import IMAGES_DIR, ImageStore
from vlln.datagen.sft.records import SFT_FILE, SUMMARY_FILE, SftRecord
from vlln.datagen.sft.sampling import SamplePlan, plan_samples
from vlln.datagen.sft.source import SourceTrajectory, open_houses, read_trajectories
from vlln.errors import ConfigError, DataFormatError
from vlln.eval.play import derive_seed
from vlln.files import write_text_atomic, writing
from vlln.prompt import (
    Conversation,
    ForwardOutput,
    PixelOutput,
    TiltDownOutput,
    build_conversation,
    connective_for,
    limit_answers,
    with_look_down,
    with_reply,
)

FORMAT_VERSION = "vlln-sft/2.0"
_OWN_ENTRIES = {SFT_FILE, SUMMARY_FILE, IMAGES_DIR}


@dataclass
class SftSummary:
    """What an export wrote (also the ``counts`` of ``export.json``)."""

    out_dir: Path
    trajectories: int = 0
    samples: int = 0
    images: int = 0
    by_kind: dict[str, int] = field(
        default_factory=lambda: {"pixel": 0, "turn": 0, "stop": 0, "dialog": 0}
    )

    def counts(self) -> dict[str, Any]:
        return {
            "trajectories": self.trajectories,
            "samples": self.samples,
            "images": self.images,
            "samples_by_kind": dict(self.by_kind),
        }


@dataclass(frozen=True)
class _Source:
    """One dataset of an export: where it is, what it holds, and its tag ("" when alone)."""

    root: Path
    houses: list[HouseDataset]
    strategy: Strategy  # from build.json ("unknown" for a folder without one)
    tag: str = ""  # "" when alone

    @property
    def task(self) -> str:
        return self.strategy.task

    @property
    def prefix(self) -> str:
        return f"{self.tag}/" if self.tag else ""


def export_sft(
    dataset_root: str | Path | Sequence[str | Path],
    out_dir: str | Path,
    config: SftConfig | None = None,
    progress: bool = True,
) -> SftSummary:
    """Export every trajectory of one built dataset, or of several mixed, into ``out_dir``."""
    config = config or SftConfig()
    sources = _sources(dataset_root)
    unknown = [str(s.root) for s in sources if s.task == "unknown"]
    if config.hard_negatives > 0 and unknown:
        raise ConfigError(
            f"{unknown[0]} has no build.json to say its task (ObjectNav has no distractors); "
            "--hard-negatives takes datasets built by `vlln data build`"
        )
    total = sum(len(house.episodes) for s in sources for house in s.houses)
    if total == 0:
        raise DataFormatError(
            f"{', '.join(str(s.root) for s in sources)} kept no trajectory, so there is nothing "
            "to export; `vlln data stats` shows why, and a build with more --per-house or "
            "--houses keeps some"
        )
    out = Path(out_dir)
    _prepare_out(out)
    store = ImageStore(out)
    summary = SftSummary(out)
    views = DistractorViews()  # builds nothing until asked
    if config.hard_negatives > 0:
        summary.by_kind["negative"] = 0
    mix: list[dict[str, Any]] = []
    bar = tqdm(
        total=total,
        desc="export-sft",
        unit="traj",
        disable=not progress,
    )
    with bar, _lines_atomic(out / SFT_FILE) as sink, closing(views):
        for source in sources:
            before = (summary.trajectories, summary.samples)
            negatives = config.hard_negatives > 0 and source.task in DISTRACTOR_TASKS
            for house in source.houses:
                for trajectory in read_trajectories(house):
                    if source.tag:
                        trajectory = replace(trajectory, house=source.prefix + trajectory.house)
                    try:
                        shows = views.shows_distractor(house, trajectory) if negatives else None
                        _export_trajectory(
                            house, trajectory, config, store, sink, summary, source.prefix, shows
                        )
                    except FileNotFoundError as error:
                        raise DataFormatError(
                            f"{house.root}, episode {trajectory.episode_index}: {error}; the "
                            "dataset is incomplete: rebuild that house with `vlln data build`"
                        ) from error
                    summary.trajectories += 1
                    bar.update()
            mix.append(
                _mix_entry(source, summary.trajectories - before[0], summary.samples - before[1])
            )
    summary.images = len(store.written)
    document: dict[str, Any] = {
        "format_version": FORMAT_VERSION,
        "vlln_version": __version__,
        "files": {"conversations": SFT_FILE, "images": f"{IMAGES_DIR}/"},
        "settings": config.to_json(),
        "preset": _preset_of(sources),
        "houses": [s.prefix + house.root.name for s in sources for house in s.houses],
        "counts": summary.counts(),
    }
    if len(sources) > 1:
        document["datasets"] = mix
        document["counts_by_task"] = _by_task(mix)
    write_text_atomic(out / SUMMARY_FILE, json.dumps(document, indent=2) + "\n")
    return summary


def _sources(dataset_root: str | Path | Sequence[str | Path]) -> list[_Source]:
    """The datasets to export, each tagged by its task where there are several."""
    roots = [dataset_root] if isinstance(dataset_root, str | Path) else list(dataset_root)
    if not roots:
        raise ConfigError("no dataset given; name one or more folders made by `vlln data build`")
    resolved = [Path(root).resolve() for root in roots]
    twice = sorted({str(r) for r in resolved if resolved.count(r) > 1})
    if twice:
        raise ConfigError(f"{twice[0]} is given more than once; name each dataset once")
    sources = [_Source(Path(root), open_houses(root), _strategy(Path(root))) for root in roots]
    if len(sources) == 1:
        return sources
    tasks = Counter(source.task for source in sources)
    seen: Counter[str] = Counter()
    tagged = []
    for source in sources:
        seen[source.task] += 1
        tag = source.task if tasks[source.task] == 1 else f"{source.task}-{seen[source.task]}"
        tagged.append(replace(source, tag=tag))
    return tagged


def _strategy(root: Path) -> Strategy:
    """How a dataset was built ("unknown" for a folder without ``build.json``)."""
    return recorded_strategy(root) or Strategy("unknown", "unknown", "unknown")


def _preset_of(sources: list[_Source]) -> str:
    """The preset of every source's houses, or ``mixed``."""
    presets = {source.strategy.preset for source in sources}
    return presets.pop() if len(presets) == 1 else "mixed"


def _mix_entry(source: _Source, trajectories: int, samples: int) -> dict[str, Any]:
    return {
        "tag": source.tag,
        "path": str(source.root),
        "task": source.task,
        "policy": source.strategy.policy,
        "preset": source.strategy.preset,
        "houses": [house.root.name for house in source.houses],
        "trajectories": trajectories,
        "samples": samples,
    }


def _by_task(mix: list[dict[str, Any]]) -> dict[str, dict[str, int]]:
    totals: dict[str, dict[str, int]] = {}
    for entry in mix:
        counts = totals.setdefault(entry["task"], {"trajectories": 0, "samples": 0})
        counts["trajectories"] += entry["trajectories"]
        counts["samples"] += entry["samples"]
    return totals


def sample_conversation(
    trajectory: SourceTrajectory, plan: SamplePlan, answers_left: int, config: SftConfig
) -> Conversation:
    """The conversation of one sample, built by the prompt functions the agents call: the
    questions heard before the frame (and, for a dialog sample, those asked at it), answers
    after the first ``answers_left`` replaced by the question-limit answer, then the move."""
    frame = plan.frame
    heard = [
        exchange
        for exchange in trajectory.exchanges
        if exchange.frame < frame or (plan.with_dialog and exchange.frame == frame)
    ]
    key = trajectory.episode_key
    seed = agent_seed(config.seed, trajectory)
    conversation = build_conversation(
        trajectory.instruction,
        frame,
        limit_answers(heard, answers_left),
        connective=connective_for(seed, key, frame),
        history_count=config.history_frames,
    )
    if isinstance(plan.move, PixelOutput):
        conversation = with_reply(conversation, TiltDownOutput())
        down = connective_for(seed, key, frame, look_down=True)
        conversation = with_look_down(conversation, frame, connective=down)
    return with_reply(conversation, plan.move)


def agent_seed(seed: int, trajectory: SourceTrajectory) -> int:
    """The seed a model agent gets in ``vlln eval --seed seed`` for the trajectory's episode:
    its prompts pick their connectives from it, so a sample's text is byte for byte what the
    agent sends in the same state, not merely drawn alike."""
    return derive_seed(seed, "agent", trajectory.scene_id, trajectory.episode_key)


def _answers_left_draws(trajectory: SourceTrajectory, config: SftConfig) -> np.random.Generator:
    """The generator of one trajectory's question-limit draws: from the seed and the
    trajectory alone, so an export is the same whatever else the dataset holds."""
    name = zlib.crc32(f"{trajectory.house}/{trajectory.episode_index}".encode())
    return np.random.default_rng(np.random.SeedSequence([config.seed, name, 11]))


def _export_trajectory(
    house: HouseDataset,
    trajectory: SourceTrajectory,
    config: SftConfig,
    store: ImageStore,
    sink: IO[str],
    summary: SftSummary,
    prefix: str = "",
    shows_distractor: Callable[[int], bool] | None = None,
) -> None:
    rng = _answers_left_draws(trajectory, config)
    for plan in plan_samples(trajectory, config, shows_distractor):
        kind: str = plan.kind
        if kind == "step":
            kind = {PixelOutput: "pixel", ForwardOutput: "forward"}.get(type(plan.move), "turn")
        for copy in range(plan.copies):
            answers_left = int(rng.integers(config.min_answers, config.max_answers + 1))
            conversation = sample_conversation(trajectory, plan, answers_left, config)
            paths = [
                store.add(house, trajectory.episode_index, ref, prefix)
                for ref in conversation.images
            ]
            sample_id = (
                f"{trajectory.house}/episode_{trajectory.episode_index:06d}/"
                f"frame_{plan.frame:06d}/{plan.kind}/{copy}"
            )
            with writing(store.out / SFT_FILE):
                sink.write(SftRecord(sample_id, tuple(paths), conversation.turns).line())
            summary.samples += 1
            summary.by_kind[kind] = summary.by_kind.get(kind, 0) + 1


def _prepare_out(out: Path) -> None:
    """Make ``out`` ready: new, empty, or an earlier export (whose output is removed)."""
    if out.exists() and not out.is_dir():
        raise ConfigError(f"{out} exists and is not a folder; choose a folder for the export")
    out.mkdir(parents=True, exist_ok=True)
    entries = {entry.name for entry in out.iterdir()}
    foreign = sorted(name for name in entries - _OWN_ENTRIES if not name.startswith("."))
    if foreign:
        shown = ", ".join(foreign[:5])
        raise ConfigError(
            f"{out} holds files that are not an export ({shown}); choose an empty or new "
            "folder, or one an earlier export wrote"
        )
    (out / SUMMARY_FILE).unlink(missing_ok=True)
    shutil.rmtree(out / IMAGES_DIR, ignore_errors=True)


@contextmanager
def _lines_atomic(path: Path) -> Iterator[IO[str]]:
    """A text file written through a temporary file renamed into place once complete; a
    failed write of it is a WriteError naming ``path``, and the temporary file is removed."""
    with writing(path):
        fd, temp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    handle = os.fdopen(fd, "w", encoding="utf-8", newline="\n")
    try:
        yield handle
        with writing(path):
            handle.flush()
            os.fsync(handle.fileno())
            handle.close()
            os.chmod(temp, 0o644)
            os.replace(temp, path)
    except BaseException:
        with suppress(OSError):  # what is left in its buffer may not fit either
            handle.close()
        Path(temp).unlink(missing_ok=True)
        raise
