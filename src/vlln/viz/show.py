"""`vlln world show`: a top-down map and egocentric RGB, depth and instance-id views of a house,
generated or read from a scanned scene folder."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from vlln.files import replace_folder
from vlln.sim.agent import AgentState
from vlln.sim.simulator import Simulator
from vlln.viz.frames import depth_image, instance_image, save_png
from vlln.viz.topdown import save_house_map
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.generator.presets import generate_preset_house
from vlln.world.model import House, Room
from vlln.world.scans import load_scene

TURNS = 12  # candidate headings per viewpoint, 30 degrees apart


@dataclass(frozen=True)
class View:
    room: Room
    state: AgentState


def polygon_area(room: Room) -> float:
    pts = np.asarray(room.polygon)
    x, z = pts[:, 0], pts[:, 1]
    return float(abs(np.dot(x, np.roll(z, 1)) - np.dot(z, np.roll(x, 1))) / 2.0)


def pick_views(sim: Simulator, n_views: int) -> list[View]:
    """One view in each of the largest rooms, facing the heading that sees the most objects."""
    rooms = sorted(sim.house.rooms, key=polygon_area, reverse=True)[:n_views]
    views = []
    for room in rooms:
        cx, cz = np.mean(np.asarray(room.polygon), axis=0)
        plane = sim.storeys.grids[room.level] if sim.storeys is not None else sim.grid
        x, z = plane.snap_point(float(cx), float(cz))
        best_yaw, best_count = 0.0, -1
        for k in range(TURNS):
            yaw = -math.pi + 2.0 * math.pi * k / TURNS
            ids = sim.render(AgentState((x, room.floor_y, z), yaw, 0.0)).instance_ids
            count = len(np.unique(ids[ids > 0]))
            if count > best_count:
                best_yaw, best_count = yaw, count
        views.append(View(room, AgentState((x, room.floor_y, z), best_yaw, 0.0)))
    return views


def show_world(
    seed: int,
    out: Path,
    n_views: int,
    params: HouseParameters | None = None,
    scene: Path | None = None,
    preset: str | None = None,
) -> list[Path]:
    """Generate house ``seed`` (of ``preset`` when given, or import the scanned scene folder
    ``scene``) and write its map and views under ``out``, replacing an earlier output folder
    of this command (:func:`vlln.files.replace_folder`); returns the files."""
    if scene is not None:
        house = load_scene(scene)
    elif preset is not None:
        house = generate_preset_house(seed, preset)
    else:
        house = generate_house(seed, params)
    files = replace_folder(out, lambda folder: _write_views(house, folder, n_views), _is_ours)
    return [out / path.name for path in files]


def _is_ours(path: Path) -> bool:
    """What `world show` writes: map.png and view*.png."""
    return path.is_file() and path.suffix == ".png" and path.name.startswith(("map", "view"))


def _write_views(house: House, out: Path, n_views: int) -> list[Path]:
    written = [out / "map.png"]
    with Simulator(house) as sim:
        save_house_map(house, written[0], sim.nav)
        max_depth = sim.config.camera.max_depth
        for index, view in enumerate(pick_views(sim, n_views)):
            for tilt_name, tilt in (("level", 0.0), ("down", -math.pi / 6)):
                state = AgentState(view.state.position, view.state.yaw, tilt)
                frame = sim.render(state)
                stem = f"view{index}_{view.room.type.replace(' ', '_')}_{tilt_name}"
                images = {
                    "rgb": frame.rgb,
                    "depth": depth_image(frame.depth, max_depth),
                    "ids": instance_image(frame.instance_ids),
                }
                for kind, image in images.items():
                    path = out / f"{stem}_{kind}.png"
                    save_png(image, path)
                    written.append(path)
    return written
