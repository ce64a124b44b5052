"""``--forward-steps``: every frame an imitator of the export stands at has a decision to copy.

The reference's sampling leaves a forward frame bare when no later position shows on its
look-down image (the floor shows from about 0.67 m ahead), so an agent that copies the export
exactly stops there: on real builds most teacher trajectories cannot be finished that way."""

from __future__ import annotations

from pathlib import Path

import pytest
from tests.datagen.sft.conftest import HandDataset
from tests.datagen.sft.samples import episode_samples, read_samples, sample_key

from vlln.datagen.build import BuildConfig, build_dataset
from vlln.datagen.collector.collect import CollectorConfig
from vlln.datagen.sft import SftConfig, export_sft
from vlln.datagen.sft.sampling import imitator_reaches_stop
from vlln.datagen.sft.source import open_houses, read_trajectories


def test_the_bare_forward_frame_of_the_golden_trajectory_gets_one_step(
    hand_dataset: HandDataset, tmp_path: Path
) -> None:
    """L L F F F F R S with questions at frames 0 and 6: frame 4 steps forward with no goal in
    view; the reference writes nothing there, --forward-steps one <move>↑."""
    export_sft(hand_dataset.root, tmp_path, SftConfig(forward_steps=True), progress=False)
    golden = episode_samples(read_samples(tmp_path), 0)
    steps = {
        sample_key(s)[1]: s["conversations"][-1]["value"] for s in golden if "/step/" in s["id"]
    }
    assert steps == {0: "<move>←←", 4: "<move>↑"}


@pytest.mark.slow
def test_an_imitator_finishes_every_teacher_trajectory_only_with_forward_steps(
    tmp_path: Path,
) -> None:
    # The second episode never finds its target: 250 steps, not the default 500, say so.
    collector = CollectorConfig(max_steps=250)
    config = BuildConfig(houses=1, per_house=4, preset="small", collector=collector)
    data = build_dataset(tmp_path, config, progress=False)
    trajectories = [t for house in open_houses(data) for t in read_trajectories(house)]
    reference = [imitator_reaches_stop(t, SftConfig()) for t in trajectories]
    filled = [imitator_reaches_stop(t, SftConfig(forward_steps=True)) for t in trajectories]
    assert all(filled) and len(filled) >= 3
    assert not all(reference)  # the reference's sampling strands an imitator somewhere
