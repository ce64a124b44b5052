"""`make demo`: the main job on the built-in houses.

It shows a house, builds test episodes on a few built-in houses of the ``small`` preset (the
benchmark's ``mp3d`` houses take minutes per run, see ``vlln bench fidelity``), runs the
frontier agent on IIGN at every dialog budget from 0 (no dialog) to 5, prints the metric table
with SR per budget and MSP, and writes the evaluation report. Rerunning resumes where it stopped.
"""

from __future__ import annotations

from pathlib import Path

from vlln.eval.config import EvalConfig
from vlln.eval.report import write_report
from vlln.eval.run_dir import summary_md_file
from vlln.eval.runner import run_evaluation
from vlln.tasks.splits import house_seeds
from vlln.viz.show import show_world
from vlln.world.generator.presets import SMALL

DEMO_HOUSES = 3
DEMO_EPISODES = 24
DEMO_BUDGETS = (0, 1, 2, 3, 4, 5)


def run_demo(out: Path) -> None:
    """Write a house's pictures, the frontier agent's IIGN run and its report under ``out``."""
    first_house = house_seeds("test", 1)[0]
    pictures = show_world(first_house, out / "house", n_views=2)
    print(f"house {first_house}: map and views in {pictures[0].parent}")
    config = EvalConfig(
        agent="frontier",
        task="iign",
        split="test",
        episodes=DEMO_EPISODES,
        budgets=DEMO_BUDGETS,
        houses=DEMO_HOUSES,
        preset=SMALL.name,
    )
    run = out / "frontier_iign"
    outcome = run_evaluation(config, run, cache_dir=out / "episodes")
    print(summary_md_file(run).read_text(encoding="utf-8"))
    files = write_report([run], out / "report")
    print(f"{len(outcome.records)} episodes in {run}; report: {files[-1]}")
