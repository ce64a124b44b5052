"""`vlln bench gpu-check` (``scripts/gpu-check.sh``): what a GPU machine gives the pipeline,
measured on Qwen2.5-VL-3B-Instruct's architecture with random weights (nothing downloaded).

In order: the model is built (:mod:`vlln.train.released`; ``--tiny``: the tiny model of
:mod:`vlln.train.scratch`, so the check runs on a CPU), a small training export is made
(``vlln data build`` + ``export-sft``), ``vlln train sft`` takes ``--sft-steps`` steps on it,
the ``vlln`` agent plays the same episodes at ``--concurrent`` 1 and 4 with the evaluation
runner (about ``--decisions`` model calls each; a random model's replies are unreadable, so
each call is one step), and the renderer's figures come from ``vlln bench sim``. Every figure
is one JSON line (``--json``); a stage that fails prints a note and the others still run.
Decisions per second are timed after the model is loaded and warm; the two runs must write
the same records (``side_by_side_records_match``).
"""

from __future__ import annotations

import contextlib
import gc
import json
import math
import sys
import tempfile
import time
import traceback
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from vlln.agents.local.dependencies import require_model_extra
from vlln.bench.figures import Figure, emit
from vlln.bench.settings import GpuCheckBench, SimBench
from vlln.errors import ConfigError

CONCURRENCY = (1, 4)
"""Episodes side by side in the two timed runs."""
DATA_HOUSES, DATA_PER_HOUSE = 1, 1  # the training export: one trajectory, some 20 samples


class _Check:
    """The figures so far and how they are printed."""

    def __init__(self, as_json: bool) -> None:
        self.as_json = as_json
        self.figures: list[Figure] = []

    def record(self, metric: str, value: float, unit: str) -> None:
        figure = Figure(metric, value, unit)
        self.figures.append(figure)
        emit(figure, self.as_json)

    def note(self, text: str) -> None:
        print(json.dumps({"note": text}) if self.as_json else f"note: {text}", flush=True)

    @contextmanager
    def stage(self, name: str) -> Iterator[None]:
        """Run a stage; its failure is a note (with where it failed), not the end."""
        try:
            yield
        except Exception as error:  # a failed stage (out of memory, an old library) is a finding
            where = traceback.extract_tb(error.__traceback__)[-1]
            self.note(
                f"{name} failed: {type(error).__name__}: {' '.join(str(error).split())[:300]} "
                f"(at {Path(where.filename).name}:{where.lineno})"
            )


def run_gpu_check(settings: GpuCheckBench) -> list[Figure]:
    """Build, train, play and render, printing each figure (module doc)."""
    require_model_extra()
    import torch

    check = _Check(settings.as_json)
    if settings.torch_threads is not None:
        torch.set_num_threads(settings.torch_threads)
    device = settings.device or ("cuda" if torch.cuda.is_available() else "cpu")
    check.note(_machine(torch, device))
    with tempfile.TemporaryDirectory(prefix="vlln-gpu-check-") as scratch:
        work = settings.work or Path(scratch)
        work.mkdir(parents=True, exist_ok=True)
        model = _build_model(settings, device, work / "model", check)
        with check.stage("training data"):
            export = _training_export(work, settings.seed)
            with check.stage("sft"):
                _train(settings, model, export, work / "sft", check)
        _free(torch)
        with check.stage("decisions"):
            _decisions(settings, model, device, work, check)
        _free(torch)
    with check.stage("renderer"):
        frames = 30 if settings.tiny else 300
        sim = SimBench(frames=frames, repeats=1 if settings.tiny else 3, as_json=settings.as_json)
        from vlln.bench.sim import run_sim_benchmark

        check.figures += run_sim_benchmark(sim)
    return check.figures


def _machine(torch: Any, device: str) -> str:
    """Which torch, transformers and device the figures are of."""
    import transformers

    where = device
    if device.startswith("cuda"):
        where += f" ({torch.cuda.get_device_name(torch.device(device))})"
    return (
        f"torch {torch.__version__}, transformers {transformers.__version__}, {where}, "
        f"{torch.get_num_threads()} torch CPU threads"
    )


def _build_model(settings: GpuCheckBench, device: str, out: Path, check: _Check) -> Path:
    """The tiny model, or the 3B architecture in bfloat16 (float32 on a CPU)."""
    import torch

    from vlln.train.released import build_released_architecture
    from vlln.train.scratch import build_tiny_model

    started = time.perf_counter()
    if settings.tiny:
        path = build_tiny_model(out, seed=settings.seed)
    else:
        dtype = torch.bfloat16 if device.startswith("cuda") else torch.float32
        path = build_released_architecture(out, seed=settings.seed, device=device, dtype=dtype)
    check.record("model_build_s", time.perf_counter() - started, "s")
    check.note(f"model: {'tiny' if settings.tiny else 'qwen2.5-vl-3b-instruct'} in {path}")
    return path


def _training_export(work: Path, seed: int) -> Path:
    """``vlln data build`` of one training house, then ``vlln data export-sft``."""
    from vlln.datagen.build import BuildConfig, build_dataset
    from vlln.datagen.sft.export import export_sft

    dataset, export = work / "dataset", work / "export"
    config = BuildConfig(houses=DATA_HOUSES, per_house=DATA_PER_HOUSE, seed=seed, preset="small")
    build_dataset(dataset, config, progress=False)
    summary = export_sft(dataset, export, progress=False)
    if summary.samples == 0:
        raise ConfigError(f"the training export in {export} holds no samples")
    return export


def _train(settings: GpuCheckBench, model: Path, export: Path, out: Path, check: _Check) -> None:
    """``vlln train sft`` for ``sft_steps`` steps (the paper's settings otherwise)."""
    from vlln.train.config import TrainConfig
    from vlln.train.sft import train_sft

    config = TrainConfig.build(
        {
            "data_dir": export,
            "model": str(model),
            "out_dir": out,
            "max_steps": settings.sft_steps,
            "workers": 0,
            "save_steps": settings.sft_steps + 1,  # no checkpoint but the final model
            "logging_steps": 1,
        }
    )
    with contextlib.redirect_stdout(sys.stderr):  # the Trainer's log lines are not figures
        outcome = train_sft(config)
    check.record("sft_steps", outcome.steps, "steps")
    check.record("sft_steps_per_s", outcome.steps / outcome.seconds, "steps/s")
    samples = outcome.steps * config.batch_size * config.grad_accumulation
    check.record("sft_samples_per_s", samples / outcome.seconds, "samples/s")
    if outcome.losses:
        check.record("sft_last_loss", outcome.losses[-1][1], "loss")
    _peak_memory(check, "sft")


def _decisions(
    settings: GpuCheckBench, model: Path, device: str, work: Path, check: _Check
) -> None:
    """The same episodes at each concurrency: decisions per second and their ratio."""
    from vlln.agents.local.backend import load_backend
    from vlln.agents.local.batching import BatchingModel
    from vlln.eval.config import EvalConfig
    from vlln.eval.runner import load_episodes, run_evaluation

    episodes = max(CONCURRENCY)
    model = model.resolve()  # as the agent names it, so that it finds the loaded backend
    options = {"model": str(model), "device": device, "max_tokens": settings.max_tokens}
    config = EvalConfig.build(
        {
            "agent": "vlln",
            "task": "iign",
            "houses": 1,
            "episodes": episodes,
            "budgets": (0,),
            "max_steps": math.ceil(settings.decisions / episodes),
            "preset": "small",
            "seed": settings.seed,
            "agent_options": options,
        }
    )
    cache = work / "splits"
    load_episodes(config, cache, progress=False)
    started = time.perf_counter()
    backend = load_backend(str(model), device, settings.max_tokens)
    check.record("model_load_s", time.perf_counter() - started, "s")
    _warm_up(backend)
    rates: dict[int, float] = {}
    lines: dict[int, list[dict[str, Any]]] = {}
    for concurrent in CONCURRENCY:
        batches: list[BatchingModel] = []
        outcome = run_evaluation(
            config,
            work / f"eval-concurrent{concurrent}",
            cache_dir=cache,
            progress=False,
            concurrent=concurrent,
            on_model_stats=batches.append,
        )
        decisions = sum(len(record.model_calls) for record in outcome.records)
        rates[concurrent] = decisions / outcome.seconds
        check.record(f"decisions_concurrent{concurrent}", decisions, "calls")
        check.record(f"decisions_per_s_concurrent{concurrent}", rates[concurrent], "calls/s")
        if batches:
            check.note(f"concurrent {concurrent}: {batches[0].describe()}")
        lines[concurrent] = [_untimed(record) for record in outcome.records]
    low, high = CONCURRENCY
    check.record(f"decisions_speedup_{high}_vs_{low}", rates[high] / rates[low], "x")
    check.record("side_by_side_records_match", float(lines[low] == lines[high]), "bool")
    _peak_memory(check, "decisions")


def _warm_up(backend: Any) -> None:
    """One call, so that the first timed decision pays no one-off start-up."""
    import io

    from PIL import Image

    from vlln.prompt import build_conversation, connective_for

    conversation = build_conversation(
        "Search for the chair.", 0, [], connective=connective_for(0, "w", 0)
    )
    picture = io.BytesIO()
    Image.new("RGB", (384, 384), (128, 128, 128)).save(picture, format="JPEG")
    backend.generate(conversation, [picture.getvalue()] * len(conversation.images))


def _untimed(record: Any) -> dict[str, Any]:
    """An episode line without its model calls' latencies."""
    line: dict[str, Any] = record.to_json()
    for call in line["model_calls"]:
        call.pop("latency_ms", None)
    return line


def _peak_memory(check: _Check, stage: str) -> None:
    import torch

    if torch.cuda.is_available():
        check.record(
            f"{stage}_peak_gpu_memory_gib", torch.cuda.max_memory_allocated() / 2**30, "GiB"
        )
        torch.cuda.reset_peak_memory_stats()


def _free(torch: Any) -> None:
    gc.collect()
    if torch.cuda.is_available():
        torch.cuda.empty_cache()
