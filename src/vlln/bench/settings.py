"""The settings of the ``vlln bench ...`` commands, one class per command; every one prints
its figures as text or, with ``--json``, one JSON object per line. Imported when a bench
command is used."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Literal

from pydantic import AliasChoices, Field
from pydantic_settings import CliPositionalArg

from vlln.config import Config, Count
from vlln.tasks.splits import TEST_PROTOCOL_EPISODES
from vlln.world.options import PresetOptions

Storeys = Annotated[int, Field(ge=2, le=3)]


class BenchOptions(Config):
    """What every benchmark takes: how it prints its figures."""

    as_json: Annotated[bool, Field(validation_alias=AliasChoices("json", "as_json"))] = False
    """print one JSON object per line"""


class SimBench(BenchOptions):
    """``vlln bench sim``: renderer, motion and geodesic figures."""

    seed: int = 0
    """house seed"""
    frames: Count = 300
    """frames per timing"""
    repeats: Count = 3
    """passes per frame rate"""
    scene: Path | None = None
    """a scanned scene folder instead of a procedural house"""
    subdivide: Annotated[int, Field(ge=0)] = 0
    """bench a scan: house --seed exported as Matterport3D with every triangle split into 4,
    N times (as `vlln world export --subdivide N`), then imported"""
    envs: Count | None = None
    """steps/s of N environments in N processes against one (speed-up)"""


class EvalBench(BenchOptions):
    """``vlln bench eval``: episodes per hour of the evaluation runner."""

    episodes: Count = 6
    """episodes"""
    cache_dir: Path | None = None
    """where built splits are kept (none: ~/.cache/vlln)"""


class OracleBench(BenchOptions):
    """``vlln bench oracle``: answer latency of the offline oracle, the service's memory."""

    seed: int = 0
    """house seed"""
    questions: Count = 2000
    """questions"""
    service_scenes: Annotated[int, Field(ge=0)] = 64
    """houses given a session each for the service's memory figure (0: no service figures)"""


class AgentBench(BenchOptions):
    """``vlln bench agent``: a model agent's step cost outside the model."""

    seed: int = 0
    """house seed"""
    repeats: Count = 200
    """timed repeats"""


class StoreysBench(BenchOptions):
    """``vlln bench storeys``: the expert's success on targets on another storey."""

    houses: Count = 10
    """houses"""
    floors: Storeys = 2
    """storeys, 2 or 3"""
    per_house: Count = 6
    """episodes per house"""
    first_seed: Annotated[int, Field(ge=0)] = 0
    """first house seed"""


class FrontierStoreysBench(BenchOptions):
    """``vlln bench frontier-storeys``: the frontier agent's IIGN success on houses of several
    storeys."""

    houses: Count = 2
    """test houses"""
    floors: Storeys = 2
    """storeys, 2 or 3"""
    episodes: Count = 30
    """episodes"""
    seed: Annotated[int, Field(ge=0)] = 0
    """seed of the episodes, the agent and the oracle (as `vlln data episodes --seed` and
    `vlln eval --seed`)"""


class DataBench(BenchOptions):
    """``vlln bench data``: trajectories per hour of the data pipeline."""

    houses: Count = 2
    """training houses"""
    per_house: Count = 6
    """trajectories per house"""


class LearningBench(BenchOptions):
    """``vlln bench learning``: a model from scratch fits its teacher, then plays its episodes
    through vlln eval --agent vlln."""

    houses: Count = 1
    """small training houses the teacher walks"""
    per_house: Count = 3
    """teacher trajectories tried per house"""
    size: Literal["tiny", "small", "base"] = "tiny"
    """model size (vlln train new-model --size)"""
    steps: Count = 1200
    """training steps"""
    batch_size: Count = 8
    """samples per step"""
    learning_rate: Annotated[
        float, Field(gt=0, validation_alias=AliasChoices("lr", "learning_rate"))
    ] = 5e-3
    """learning rate (vision tower too: the model starts from scratch)"""
    history: Count = 128
    """history frames in each prompt (the export's --history; 128 shows every frame of these
    trajectories, so their prompts differ in text and a model from scratch fits them in
    minutes; with the reference's 8 they differ only in pixels from frame 8 on)"""
    agreement_samples: Count = 200
    """teacher decisions the agreement is measured on"""
    seed: int = 0
    """seed of data, weights and evaluation"""
    out: Path | None = None
    """keep the data, model and runs here, and resume them (none: a temporary folder)"""


class FidelityBench(BenchOptions, PresetOptions):
    """``vlln bench fidelity``: SR/SPL and the failure taxonomy beside the paper's Table 1."""

    episodes: Annotated[int, Field(ge=1, le=TEST_PROTOCOL_EPISODES)] = 200
    """episodes of test500 per run"""
    out: Path = Path("out/fidelity")
    """run folders, resumed"""
    workers: Count = 1
    """processes"""
    cache_dir: Path | None = None
    """where built splits are kept (none: ~/.cache/vlln)"""


class WebBench(BenchOptions):
    """``vlln bench web``: key-press-to-new-frame latency in the browser."""

    presses: Annotated[int, Field(ge=10)] = 200
    """key presses (at least 10: a p99 needs them)"""
    browser: str = "/usr/bin/chromium"
    """Chromium executable (Debian: chromium)"""


class WorldBench(BenchOptions, PresetOptions):
    """``vlln bench world``: catalogue size; objects, triangles and build time per house."""

    houses: Count = 20
    """houses"""
    first_seed: Annotated[int, Field(ge=0)] = 0
    """first seed"""
    test_houses: Annotated[int, Field(ge=0)] = 14
    """test houses whose statistics are printed beside the Matterport3D anchors (14: the
    whole test split; 0: none)"""


class GpuCheckBench(BenchOptions):
    """``vlln bench gpu-check``: training steps/s, decisions/s side by side, frame rate, on
    Qwen2.5-VL-3B-Instruct's architecture with random weights (``--tiny``: the tiny model)."""

    tiny: bool = False
    """the tiny model instead of the 3B architecture (runs on a CPU)"""
    decisions: Count = 50
    """model calls per timed run (4 episodes share them)"""
    sft_steps: Count = 20
    """vlln train sft steps"""
    max_tokens: Count = 128
    """longest reply in tokens (the agent's default; a random model rarely stops earlier)"""
    device: str | None = None
    """torch device (none: cuda if present, else cpu)"""
    torch_threads: Count | None = None
    """torch CPU threads (none: torch's default; 1 is often faster on a busy machine)"""
    seed: int = 0
    """seed of the weights, the data and the episodes"""
    work: Path | None = None
    """folder kept for the model, data and runs (none: a temporary one)"""


class Mp3dHouseBench(BenchOptions):
    """``vlln bench mp3d-house FILE...``: the statistics of real Matterport3D ``.house`` files
    that the mp3d preset's anchors are taken from (docs/world-statistics.md)."""

    files: Annotated[CliPositionalArg[list[Path]], Field(min_length=1)]
    """.house files (Matterport3D house_segmentations)"""


class Mp3dConnectivityBench(BenchOptions):
    """``vlln bench mp3d-connectivity FILE...``: walk lengths and storeys of Matterport3D
    buildings from their R2R connectivity graphs (docs/world-statistics.md)."""

    files: Annotated[CliPositionalArg[list[Path]], Field(min_length=1)]
    """<scan>_connectivity.json files"""


class AgreementBench(BenchOptions):
    """``vlln bench agreement``: how often a model's decision is its teacher's, on an export's
    prompts (an export of held-out houses measures what it learned, not what it memorised)."""

    model: Path
    """the model folder or checkpoint"""
    export: Path
    """the export folder (vlln data export-sft --out)"""
    samples: Count = 200
    """teacher decisions asked, spread evenly over the export"""


class OracleAnswersBench(Config):
    """``vlln bench oracle-answers QUESTIONS``: an oracle's answers to a question file, each
    asked in a real episode, for readers to judge (docs/helpful-oracle.md)."""

    questions: CliPositionalArg[Path]
    """JSON Lines, each {"question", "kind", "category"}"""
    oracle: Literal["rules", "helpful"] = "helpful"
    """who answers"""
    out: Path = Path("out/oracle-answers.jsonl")
    """the answers, one JSON line per question"""
    houses: Count = 4
    """small test houses the questions are asked in"""
    seed: Annotated[int, Field(ge=0)] = 0
    """seed of the episode, the exploration and the oracle's wording"""
    cache_dir: Path | None = None
    """where built splits are kept (none: ~/.cache/vlln)"""


class RecipeFigures(Config):
    """``vlln bench recipe-figures``: the held-out figures of scripts/cpu-recipe.sh."""

    out: Path = Path("out/recipe")
    """the recipe's folder (its OUT)"""


class DialogPolicyFigures(BenchOptions):
    """``vlln bench dialog-policy``: a learned dialog policy against the fixed triggers, paired
    over the episodes both runs played (docs/dialog-policy.md)."""

    fixed: Path
    """run directory of the frontier agent without --dialog-policy"""
    learned: Path
    """run directory of the same evaluation with --dialog-policy"""
    budget: Annotated[int, Field(ge=0)] = 5
    """dialog budget compared"""
