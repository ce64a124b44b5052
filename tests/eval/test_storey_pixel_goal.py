"""A model agent's pixel goal in a two-storey house: `<move>col row` on the look-down image
of the stairs leads up the flight to the tread the pixel shows."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from tests.eval.test_openai_vlm import episode_file, run
from tests.oracle.llm.chat_server import chat_server, completion
from tests.stairs import SCENE_ID, flight_foot, upstairs_episode
from vlln.sim.agent import AgentState
from vlln.tasks.scenes import SceneCache


@pytest.mark.slow
def test_a_pixel_on_the_stairs_leads_up_the_flight_to_the_treads_height(
    scenes: SceneCache, tmp_path: Path
) -> None:
    sim = scenes.get(SCENE_ID)
    storeys = sim.storeys
    assert storeys is not None
    flight = flight_foot(sim)
    episode = upstairs_episode(sim, "stairs-pixel")
    state = AgentState(flight.start, flight.yaw, -math.radians(30))
    spec = sim.config.camera
    fx, fy, cx, cy = spec.intrinsics()
    gx, gy, gz = flight.on_flight
    local = spec.view_matrix(state.position, state.yaw, state.tilt) @ [gx, gy, gz, 1.0]
    depth = -float(local[2])
    col, row = round(cx + fx * local[0] / depth), round(cy - fy * local[1] / depth)
    assert float(sim.render(state).depth[row, col]) == pytest.approx(depth, abs=0.05)

    script = ["<move>↓", f"<move>{col} {row}", "<move>STOP"]
    with chat_server([completion(text) for text in script]) as server:
        outcome = run(server, episode_file(tmp_path, episode), tmp_path / "run", scenes)
    (record,) = outcome.records
    assert record.failed_actions == 0 and record.failures == {}
    assert record.actions[:2] == ["LOOK_DOWN", f"PIXEL:{col},{row}"]
    walked = record.actions[2:-1]
    assert 4 <= len(walked) <= 8 and set(walked) <= {"MOVE_FORWARD", "TURN_LEFT", "TURN_RIGHT"}
    assert record.actions[-1] == "STOP"
    # The run leaves the agent where it stopped: on the tread the pixel showed, at its height.
    x, y, z = scenes.get(SCENE_ID).state.position
    assert math.hypot(x - gx, z - gz) < 0.25 + 0.1
    assert gy > storeys.floor_ys[0] + 0.5
    assert y == pytest.approx(storeys.height_at(0, x, z)) and y == pytest.approx(gy, abs=0.21)
    assert record.geodesic_trace[-1] < record.geodesic_start
