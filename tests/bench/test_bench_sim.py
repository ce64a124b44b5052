"""`vlln bench sim --json` prints one well-formed figure per line for every promised metric."""

import json
from pathlib import Path

import pytest

from vlln.cli import main
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.scans import export_scene

REQUIRED = {
    "render_fps",
    "render_cpu_ms",
    "drawn_triangles",
    "step_fps",
    "raw_raster_fps",
    "geodesic_query_us",
    "field_build_ms",
    "house_build_s",
    "sim_rss_mb",
}


@pytest.mark.slow
def test_sim_benchmark_prints_json_lines(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "sim", "--json", "--frames", "40", "--repeats", "1", "--seed", "3"]) == 0
    lines = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert all(set(line) == {"metric", "value", "unit"} for line in lines)
    values = {line["metric"]: line["value"] for line in lines}
    assert set(values) >= REQUIRED
    assert all(values[name] > 0 for name in REQUIRED)


@pytest.mark.slow
def test_parallel_environments_report_their_speed_up(capsys: pytest.CaptureFixture[str]) -> None:
    args = ["bench", "sim", "--json", "--envs", "2", "--frames", "20", "--repeats", "1"]
    assert main([*args, "--seed", "3"]) == 0
    lines = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    values = {line["metric"]: line["value"] for line in lines}
    assert values["envs"] == 2
    assert values["steps_per_s_1_env"] > 0 and values["steps_per_s_2_envs"] > 0
    expected = values["steps_per_s_2_envs"] / values["steps_per_s_1_env"]
    assert values["envs_speedup"] == pytest.approx(expected, rel=0.01)
    cores = values["cpu_cores"]
    assert values["render_threads_1_env"] == cores
    assert values["render_threads_per_env_2_envs"] == max(1, cores // 2)
    busy = values["steps_per_s_1_env"] * values["cpu_ms_per_step_1_env"] / 1e3
    assert values["cpu_cores_busy_1_env"] == pytest.approx(busy, rel=0.01, abs=0.002)
    main_ms, cpu_ms = values["main_thread_cpu_ms_per_step_1_env"], values["cpu_ms_per_step_1_env"]
    assert 0 < main_ms <= cpu_ms
    ceiling = cores * (main_ms + (cpu_ms - main_ms) / cores) / values["cpu_ms_per_step_2_envs"]
    assert values["envs_speedup_ceiling"] == pytest.approx(ceiling, rel=0.01)
    same = values["steps_per_s_2_envs"] / values["steps_per_s_1_env_same_threads"]
    assert values["envs_speedup_same_threads"] == pytest.approx(same, rel=0.01)


@pytest.mark.slow
def test_a_subdivided_scan_reports_import_and_frame_rates(
    capsys: pytest.CaptureFixture[str],
) -> None:
    args = ["bench", "sim", "--json", "--frames", "20", "--repeats", "1", "--seed", "3"]
    assert main([*args, "--subdivide", "1"]) == 0
    values = {
        line["metric"]: line["value"]
        for line in map(json.loads, capsys.readouterr().out.splitlines())
    }
    house = generate_house(3)
    assert house.geometry is not None
    assert values["house_triangles"] == 4 * house.geometry.mesh.n_triangles
    for name in ("scene_import_s", "simulator_build_s", "render_fps", "raw_raster_fps"):
        assert values[name] > 0
    assert "house_build_s" not in values and "sim_rss_mb" not in values


@pytest.mark.slow
def test_a_scanned_scene_with_several_storeys_is_measured(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    two_storeys = HouseParameters(floors=2, min_rooms=4, max_rooms=4, min_area=60.0, max_area=70.0)
    scene = export_scene(generate_house(1, two_storeys), tmp_path, "mp3d")
    args = ["bench", "sim", "--json", "--frames", "20", "--repeats", "1", "--scene", str(scene)]
    assert main(args) == 0
    values = {
        line["metric"]: line["value"]
        for line in map(json.loads, capsys.readouterr().out.splitlines())
    }
    for name in ("render_fps", "step_fps", "field_build_ms", "geodesic_query_us"):
        assert values[name] > 0
