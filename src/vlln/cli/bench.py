"""``vlln bench ...``: the speed and memory figures. Each command's flags come from its
settings class in :mod:`vlln.bench.settings`, and its benchmark function takes that class."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from vlln.cli.generated import add_config_command, calls
from vlln.cli.options import Commands


def _settings(name: str) -> Callable[[], type[Any]]:
    """The settings class ``name``, imported when its command is used."""

    def load() -> type[Any]:
        from vlln.bench import settings

        loaded: type[Any] = getattr(settings, name)
        return loaded

    return load


COMMANDS = (
    ("sim", "SimBench", ("sim:run_sim_benchmark",), "renderer, motion and geodesic figures"),
    ("eval", "EvalBench", ("eval:compare_presets",), "episodes per hour of the evaluation runner"),
    (
        "oracle",
        "OracleBench",
        ("oracle:run_oracle_benchmark",),
        "answer latency of the offline oracle",
    ),
    (
        "agent",
        "AgentBench",
        ("agent:run_agent_benchmark", "agent_model:run_model_benchmark"),
        "a model agent's step cost outside the model; the local model's steps/s",
    ),
    (
        "storeys",
        "StoreysBench",
        ("storeys:run_storeys_benchmark",),
        "the expert's success on targets on another storey (2- or 3-storey houses)",
    ),
    (
        "frontier-storeys",
        "FrontierStoreysBench",
        ("frontier_storeys:run_frontier_storeys_benchmark",),
        "the frontier agent's IIGN success on houses of several storeys",
    ),
    (
        "data",
        "DataBench",
        ("data:run_data_benchmark",),
        "trajectories per hour of the data pipeline",
    ),
    (
        "learning",
        "LearningBench",
        ("learning:run_learning_benchmark",),
        "a model from scratch fits its teacher's trajectories, then plays them in vlln eval",
    ),
    (
        "agreement",
        "AgreementBench",
        ("learning:run_agreement_benchmark",),
        "the share of an export's teacher decisions a model makes alike",
    ),
    (
        "recipe-figures",
        "RecipeFigures",
        ("recipe:print_recipe_figures",),
        "held-out SR and SPL with 95% intervals, dialog gains and the learning curve of "
        "scripts/cpu-recipe.sh",
    ),
    (
        "oracle-answers",
        "OracleAnswersBench",
        ("oracle_answers:run_oracle_answers",),
        "an oracle's answers to a question file, each asked in a real episode after exploring",
    ),
    (
        "dialog-policy",
        "DialogPolicyFigures",
        ("dialog_policy:run_dialog_policy_figures",),
        "SR and questions per episode of a learned dialog policy against the fixed triggers, "
        "with paired 95% intervals",
    ),
    (
        "fidelity",
        "FidelityBench",
        ("fidelity:run_fidelity_benchmark",),
        "SR/SPL with 95% intervals and the failure taxonomy of frontier (noisy detector) "
        "and expert on the paper's test protocol, beside the paper's Table 1",
    ),
    (
        "world",
        "WorldBench",
        ("world:run_world_benchmark",),
        "catalogue size; objects, triangles and build time per house",
    ),
    (
        "mp3d-house",
        "Mp3dHouseBench",
        ("mp3d_house:run_mp3d_house",),
        "statistics of real Matterport3D .house files, the anchors of the mp3d houses",
    ),
    (
        "mp3d-connectivity",
        "Mp3dConnectivityBench",
        ("mp3d_connectivity:run_mp3d_connectivity",),
        "walk lengths and storeys of Matterport3D buildings from R2R connectivity graphs",
    ),
    (
        "gpu-check",
        "GpuCheckBench",
        ("gpu_check:run_gpu_check",),
        "training, side-by-side decisions and frame rate on the Qwen2.5-VL-3B architecture",
    ),
    (
        "web",
        "WebBench",
        ("web:run_web_benchmark",),
        "key-press-to-new-frame latency in the browser",
    ),
)
"""Each command: its name, settings class, the ``vlln.bench`` functions it calls with them
(``module:function``) and its help."""


def add_bench_commands(commands: Commands) -> None:
    bench = commands.add_parser("bench", help="speed and memory benchmarks").add_subparsers(
        dest="bench_command", required=True
    )
    for name, settings, targets, help in COMMANDS:
        handler = calls(*(f"vlln.bench.{target}" for target in targets))
        add_config_command(bench, name, _settings(settings), handler, help=help)
