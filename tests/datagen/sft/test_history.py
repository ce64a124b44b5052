"""History sampling: evenly spread past frames plus the frames where questions were asked."""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest
from tests.datagen.sft.conftest import HandDataset
from tests.datagen.sft.samples import episode_samples, read_samples

from vlln.datagen.sft import SftConfig, export_sft
from vlln.datagen.sft.history import history_frames, uniform_frames


@pytest.mark.parametrize("frame", [9, 20, 57, 500])
def test_uniform_frames_spread_evenly_and_end_with_the_latest(frame: int) -> None:
    picked = uniform_frames(frame, 8)
    assert len(picked) == len(set(picked)) == 8
    assert picked == sorted(picked) and picked[-1] == frame - 1 and picked[0] >= 0
    gaps = {b - a for a, b in itertools.pairwise(picked)}
    assert max(gaps) - min(gaps) <= 1


def test_short_pasts_are_shown_whole() -> None:
    assert uniform_frames(0, 8) == []
    assert uniform_frames(5, 8) == [0, 1, 2, 3, 4]
    assert uniform_frames(8, 8) == list(range(8))
    assert uniform_frames(30, 0) == []
    assert uniform_frames(30, 1) == [29]


def test_dialog_frames_join_the_history_only_when_earlier() -> None:
    picked = history_frames(40, [3, 3, 12, 40, 41], 4)
    assert picked == [3, 9, 12, 19, 29, 39]
    assert history_frames(40, [], 4) == uniform_frames(40, 4)


def test_history_setting_and_the_empty_history_wording(
    hand_dataset: HandDataset, tmp_path: Path
) -> None:
    export_sft(hand_dataset.root, tmp_path, SftConfig(history_frames=0), progress=False)
    samples = read_samples(tmp_path)
    golden, scan = episode_samples(samples, 0), episode_samples(samples, 2)
    assert "You have no historical observations yet." in golden[0]["conversations"][0]["value"]
    assert "You have no historical observations yet." in scan[1]["conversations"][0]["value"]
    # Frame 2 of the golden trajectory: only frame 0, where a question was asked.
    assert golden[1]["images"][0].endswith("/level_000000.jpg")
    assert len(golden[1]["images"]) == 3
    assert (
        "These are your historical observations: <image> <dialog> "
        in (golden[1]["conversations"][0]["value"])
    )
