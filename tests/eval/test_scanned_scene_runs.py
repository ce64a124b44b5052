"""Runs over a scene in the real Matterport3D format (tests/world/mp3d_scene.py): an episode
upstairs climbs and is scored honestly, an episode that cannot be played is refused and
counted, and `vlln video`, `vlln report` and `vlln world show` work on the scan."""

from __future__ import annotations

import contextlib
import io
import json
import logging
import math
from collections.abc import Iterator
from pathlib import Path

import av
import pytest

from tests.world import mp3d_scene
from vlln.cli import main
from vlln.eval.results import read_records
from vlln.sim.agent import Action
from vlln.sim.simulator import Simulator
from vlln.tasks.env import NavigationEnv
from vlln.tasks.episode import Episode, Goal, Instruction, ViewPoint, write_episodes
from vlln.tasks.metrics import success
from vlln.tasks.scenes import SceneCache, procedural_scene_id, scan_scene_id
from vlln.tasks.spec import TaskConfig, TaskType
from vlln.world.frame import yaw_to_quaternion
from vlln.world.scans import load_scene

JOINED, APART = "2t7WUuJeko7", "8WUmhLawc2A"  # the scene, and it without its flight annotated
DOWNSTAIRS = mp3d_scene.to_vlln(6.0, 6.0, 0.0)  # far corner of the ground floor
UNDER_THE_BED = mp3d_scene.to_vlln(6.5, 3.1, 0.0)  # the bed is right above, upstairs


@pytest.fixture(scope="module")
def root(tmp_path_factory: pytest.TempPathFactory) -> Path:
    folder = tmp_path_factory.mktemp("scenes")
    mp3d_scene.write_scene(folder, JOINED)
    mp3d_scene.write_scene(folder, APART, flight=False)
    return folder


@pytest.fixture(scope="module")
def sim(root: Path) -> Iterator[Simulator]:
    with Simulator(load_scene(root / JOINED)) as simulator:
        yield simulator


def episode(
    sim: Simulator, episode_id: str, scene: str, start: tuple[float, ...], target: int
) -> Episode:
    """An IGN episode to ``target`` with its view points, as the reference writes them."""
    inst = sim.house.instance(target)
    points = sim.view_points(inst.box)
    qx, qy, qz, qw = yaw_to_quaternion(0.0)
    goal = Goal(
        inst.box.center,
        None,
        (*inst.box.min, *inst.box.max),
        tuple(ViewPoint((p[0], p[1], p[2])) for p in points[::4] if len(p) == 3),
    )
    return Episode(
        episode_id,
        scan_scene_id("mp3d", scene),
        (start[0], start[1], start[2]),
        (qx, qy, qz, qw),
        inst.category,
        (goal,),
        Instruction("ign", f"Go to the {inst.category}.", (str(inst.id),)),
        {},
    )


@pytest.fixture(scope="module")
def run(root: Path, sim: Simulator, tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, str]:
    """The expert over three episodes: upstairs in the scene (1), upstairs in the scene whose
    stairs are not annotated (2: refused) and downstairs there (3); returns the run and the
    command's stderr."""
    tmp = tmp_path_factory.mktemp("run")
    episodes = [
        episode(sim, "1", JOINED, DOWNSTAIRS, mp3d_scene.BED_ID),
        episode(sim, "2", APART, DOWNSTAIRS, mp3d_scene.BED_ID),
        episode(sim, "3", APART, DOWNSTAIRS, mp3d_scene.COUCH_ID),
    ]
    path = tmp / "ign.json.gz"
    write_episodes(path, episodes)
    out = tmp / "run"
    args = ["eval", "--agent", "expert", "--task", "ign", "--episode-file", str(path)]
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        code = main([*args, "--scenes", str(root), "--out", str(out), "--quiet"])
    assert code == 0, err.getvalue()
    return out, err.getvalue()


@pytest.mark.slow
def test_the_episode_upstairs_climbs_and_is_scored_honestly(
    run: tuple[Path, str], sim: Simulator
) -> None:
    out, _ = run
    records = {r.episode_id: r for r in read_records(out / "episodes.jsonl")}
    record = records["1"]
    assert record.error is None and record.end_reason == "stop" and success(record)
    assert record.stop_instance_id == mp3d_scene.BED_ID
    assert max(record.heights) == pytest.approx(mp3d_scene.UPPER)  # it climbed
    assert record.heights[0] == 0.0 and record.heights[-1] == pytest.approx(mp3d_scene.UPPER)
    foot = mp3d_scene.to_vlln(0.6, mp3d_scene.FOOT_Y, 0.0)
    to_foot = math.dist((DOWNSTAIRS[0], DOWNSTAIRS[2]), (foot[0], foot[2]))
    flight = math.hypot(mp3d_scene.HEAD_Y - mp3d_scene.FOOT_Y, mp3d_scene.UPPER)
    assert record.geodesic_start > to_foot + flight  # the distance goes up the stairs
    assert record.path_length >= record.geodesic_start - 0.3


def test_a_stop_under_the_target_is_no_success(sim: Simulator, root: Path) -> None:
    """The bed is right above the start: on the ground floor's plan it is one step away."""
    cache = SceneCache(scenes_dir=root)
    try:
        start = episode(sim, "9", JOINED, UNDER_THE_BED, mp3d_scene.BED_ID)
        env = NavigationEnv([start], TaskConfig(task=TaskType.IGN, dialog_budget=0), cache)
        env.reset(options={"episode_index": 0})
        env.step(Action.STOP)
        record = env.record("stop")
    finally:
        cache.close()
    assert not success(record)
    assert record.geodesic_start > 10.0 and record.geodesic_trace[-1] > 10.0


def test_an_unjoined_storey_refuses_the_episode_and_the_run_goes_on(
    run: tuple[Path, str], root: Path
) -> None:
    out, err = run
    refused = [line for line in err.splitlines() if line.startswith("refused:")]
    assert refused == [
        f"refused: episode 2 in {scan_scene_id('mp3d', APART)} is refused: no stairs join its "
        "start on storey 0 to its goals on storey 1 (the scene's flights that could join them "
        "were left out or are missing)"
    ]
    records = {r.episode_id: r for r in read_records(out / "episodes.jsonl")}
    assert sorted(records) == ["1", "3"]
    assert success(records["3"])  # the ground floor of that scene plays
    health = next(line for line in err.splitlines() if line.startswith("run health"))
    assert health.startswith("run health: complete, 2 of 3 episode lines and 1 refused")
    assert "refused episodes 1 (2 (mp3d/8WUmhLawc2A/8WUmhLawc2A.glb): no stairs join" in health


def test_score_counts_the_refused_episode(
    run: tuple[Path, str], capsys: pytest.CaptureFixture[str]
) -> None:
    out, _ = run
    assert main(["score", str(out), "--json"]) == 0
    captured = capsys.readouterr()
    assert "refused episodes 1" in captured.err
    health = json.loads(captured.out)["health"]
    assert health["complete"] and health["refused_lines"] == 1
    assert health["refused_episodes"][0].startswith("2 (mp3d/8WUmhLawc2A")


@pytest.mark.slow
def test_vlln_video_reads_the_scan_from_the_run(run: tuple[Path, str], tmp_path: Path) -> None:
    out, _ = run
    target = tmp_path / "up.mp4"
    assert main(["video", str(out), "--episode", "1", "--out", str(target)]) == 0
    record = next(r for r in read_records(out / "episodes.jsonl") if r.episode_id == "1")
    with av.open(str(target)) as container:
        frames = sum(1 for _ in container.decode(container.streams.video[0]))
    assert frames == len(record.actions) + 1


@pytest.mark.slow
def test_vlln_report_draws_the_scan(run: tuple[Path, str], tmp_path: Path) -> None:
    out, _ = run
    report = tmp_path / "report"
    assert main(["report", str(out), "--out", str(report), "--videos", "1"]) == 0
    html = (report / "report.html").read_text(encoding="utf-8")
    assert "has no map" not in html
    assert len(list(report.glob("map_*.png"))) == 2 and len(list(report.glob("*.mp4"))) == 1
    assert "map_0_1_b0.png" in html and "refused episodes 1" in html


@pytest.mark.slow
def test_world_show_accepts_a_scan_folder(root: Path, tmp_path: Path) -> None:
    out = tmp_path / "show"
    args = ["world", "show", "--scene", str(root / JOINED), "--out", str(out), "--views", "2"]
    assert main(args) == 0
    assert (out / "map.png").stat().st_size > 10_000
    views = sorted(out.glob("view*_level_rgb.png"))
    assert len(views) == 2


@pytest.mark.slow
def test_a_procedural_episode_with_scenes_is_said_so(
    root: Path, caplog: pytest.LogCaptureFixture
) -> None:
    cache = SceneCache(scenes_dir=root)
    scenes = [procedural_scene_id(3), procedural_scene_id(3), procedural_scene_id(4)]
    with caplog.at_level(logging.WARNING):
        houses = [cache._house(scene) for scene in scenes]
    said = [r.getMessage() for r in caplog.records]
    assert len(said) == 1 and said[0].startswith(f"{scenes[0]} names a procedural house")
    assert f"not read from --scenes {root}" in said[0]
    assert [house.seed for house in houses] == [3, 3, 4]


@pytest.mark.slow
def test_episodes_written_for_an_exported_scan_name_it_and_play_on_it(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    from vlln.tasks.episode import read_episodes

    out = tmp_path / "scans"
    assert (
        main(["world", "export", "--seed", "3", "--style", "mp3d", "--episodes", "--out", str(out)])
        == 0
    )
    path = out / "mp3d" / "house_00003_ign.json.gz"
    episodes = read_episodes(path)
    assert episodes and {e.scene_id for e in episodes} == {"mp3d/house_00003/house_00003.glb"}
    assert (out / "mp3d" / "house_00003_iign.json.gz").is_file()
    run = tmp_path / "run"
    args = ["eval", "--agent", "expert", "--task", "ign", "--episode-file", str(path)]
    with caplog.at_level(logging.WARNING):
        assert (
            main(
                [
                    *args,
                    "--episodes",
                    "1",
                    "--scenes",
                    str(out / "mp3d"),
                    "--out",
                    str(run),
                    "--quiet",
                ]
            )
            == 0
        )
    assert "names a procedural house" not in caplog.text
    (record,) = read_records(run / "episodes.jsonl")
    assert record.scene_id == "mp3d/house_00003/house_00003.glb" and success(record)
    stored = json.loads((run / "run.json").read_text(encoding="utf-8"))
    assert stored["scenes"] == str((out / "mp3d").resolve())
