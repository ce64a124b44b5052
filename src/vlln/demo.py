"""`make demo`: the main job on the built-in houses."""

from __future__ import annotations

from pathlib import Path

from vlln.viz.show import show_world

DEMO_SEEDS = (0, 1, 2)


def run_demo(out: Path) -> None:
    """Generate the demo houses and write a map and egocentric views of each."""
    for seed in DEMO_SEEDS:
        files = show_world(seed, out / f"house_{seed:05d}")
        print(f"house {seed}: {len(files)} images in {files[0].parent}")
