"""Episode videos: replayed frames, `vlln video`, and the report's videos playing in Chromium."""

from __future__ import annotations

from pathlib import Path

import av
import pytest
from playwright.sync_api import sync_playwright

from tests.eval.runs import evaluate
from vlln.cli import main
from vlln.eval.options import ReportOptions
from vlln.eval.report import write_report
from vlln.eval.results import read_records
from vlln.eval.video import VideoConfig, map_images, replay
from vlln.eval.videos import dialog_first
from vlln.sim.simulator import Simulator
from vlln.tasks.scenes import SceneCache

CHROMIUM = "/usr/bin/chromium"  # Debian's chromium, installed by scripts/setup.sh

_DURATION = """() => new Promise((resolve, reject) => {
  const video = document.querySelector("video");
  const done = () => resolve([video.duration, video.videoWidth, video.videoHeight]);
  if (video.readyState >= 2) done();
  video.addEventListener("loadeddata", done);
  video.addEventListener("error", () => reject("cannot play: " + video.error.code));
})"""


@pytest.fixture(scope="module")
def dialog_run(
    tmp_path_factory: pytest.TempPathFactory, split_cache: Path, scenes: SceneCache
) -> Path:
    out = tmp_path_factory.mktemp("video_run")
    evaluate(out, split_cache, scenes, agent="frontier", episodes=1, budgets=(5,), max_steps=30)
    return out


def test_replay_follows_the_recorded_poses(dialog_run: Path, scenes: SceneCache) -> None:
    [record] = read_records(dialog_run / "episodes.jsonl")
    sim: Simulator = scenes.get(record.scene_id)
    steps = list(replay(record, sim))
    assert len(steps) == len(record.actions) + 1
    assert [step.turn for step in steps if step.turn is not None] == record.dialog
    last = steps[-1].state
    x, z, yaw = record.positions[-1]
    assert (last.position[0], last.position[2], last.yaw) == (x, z, yaw)


@pytest.mark.slow
def test_vlln_video_writes_an_mp4_of_the_dialog_episode(dialog_run: Path, tmp_path: Path) -> None:
    target = tmp_path / "episode.mp4"
    assert main(["video", str(dialog_run), "--out", str(target)]) == 0
    [record] = read_records(dialog_run / "episodes.jsonl")
    assert record.dialog, "the frontier agent asks its colour question first"
    config = VideoConfig()
    held = round(config.hold_s * config.fps) - 1
    with av.open(str(target)) as container:
        stream = container.streams.video[0]
        frames = sum(1 for _ in container.decode(stream))
        assert (stream.width, stream.height) == (640 + config.map_size, 480 + config.caption_height)
    assert frames == len(record.actions) + 1 + held * len(record.dialog)


@pytest.mark.slow
def test_report_video_plays_in_headless_chromium(dialog_run: Path, tmp_path: Path) -> None:
    files = write_report([dialog_run], tmp_path, ReportOptions(samples=0, videos=1))
    [video] = [path for path in files if path.suffix == ".mp4"]
    [record] = dialog_first(read_records(dialog_run / "episodes.jsonl"), 1)
    with av.open(str(video)) as container:
        expected = container.streams.video[0].frames / VideoConfig().fps
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"])
        try:
            page = browser.new_page()
            page.goto((tmp_path / "report.html").as_uri())
            duration, width, height = page.evaluate(_DURATION)
        finally:
            browser.close()
    assert duration == pytest.approx(expected, abs=0.3)
    assert duration > len(record.actions) / VideoConfig().fps
    assert (width, height) == (1120, 592)


def test_the_map_panel_shows_the_whole_floor_plan(dialog_run: Path, scenes: SceneCache) -> None:
    [record] = read_records(dialog_run / "episodes.jsonl")
    house = scenes.get(record.scene_id).house
    size = VideoConfig().map_size
    plans, to_pixel = map_images(house, record, size)
    corners = [to_pixel(x, z) for room in house.rooms for x, z in room.polygon]
    assert all(0 <= u <= size and 0 <= v <= size for u, v in corners)
    drawn = (plans[0] < 240).any(axis=2).mean()
    assert drawn > 0.4, f"only {drawn:.0%} of the panel shows the plan"
