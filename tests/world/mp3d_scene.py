"""A two-storey scene written in the real Matterport3D format, from the format's description
(docs/scans.md; Matterport ``data_organization.md``, habitat-sim ``Mp3dSemanticScene.cpp``)
and the shape of real ``.house`` files, never from vlln's exporter.

The ``.house`` file has the real records, token counts and order (H 29, L 18, R 20, S 22,
V 13, P 13, I 41, C 11, O 24, E 19 tokens; H, L, R, S, V, P, I, C, O, E), fields grouped
by double spaces and numbers written as C++ streams write them (6 significant digits). Its
C records are rows of Matterport's ``category_mapping.tsv`` with their real mapping index,
raw name (``#`` for spaces) and mpcat40 group (real files list all 1,659 rows; this one lists
the rows it uses). The ``.glb`` is a z-up mesh made with trimesh from boxes and quads.

The house, in the scan's frame (metres, z up): an 8 x 7 m footprint, ground floor at z = 0,
upper floor at z = 2.8. A straight flight of 16 rises of 0.175 m climbs along +y against the
wall x = 0 (x in [0, 1.2], foot at y = 1.0, 15 treads of 0.26 m up to y = 4.9): its last rise
steps onto the upper floor, which is the top landing, and its annotated box (raw category
``steps``, mpcat40 ``stairs``) ends 5 cm below that floor, as real boxes do. A wall beside the
flight, one under its head (lower storey) and one above its foot (upper storey) close the
stairwell. Objects: a couch and a table downstairs, a bed, a nightstand and a chair upstairs,
plus a ``remove`` (mpcat40 void) and an ``unknown`` (mpcat40 misc) box and a box of no
category (-1), which are not objects, and ``wall``/``floor`` annotations, which are structure.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import trimesh

UPPER = 2.8  # z of the upper floor
RISES = 16
RISE = UPPER / RISES
TREAD = 0.26
FOOT_Y, HEAD_Y = 1.0, 1.0 + (RISES - 1) * TREAD  # 4.9
FLIGHT_X = (0.0, 1.2)
WIDTH, DEPTH, ROOF = 8.0, 7.0, 5.4

# (mapping index, raw name, mpcat40 index, mpcat40 name): rows of category_mapping.tsv.
CATEGORY_ROWS = (
    (1, "wall", 1, "wall"),
    (3, "ceiling", 17, "ceiling"),
    (4, "floor", 2, "floor"),
    (9, "remove", 0, "void"),
    (15, "table", 5, "table"),
    (24, "couch", 10, "sofa"),
    (26, "bed", 11, "bed"),
    (27, "nightstand", 13, "chest_of_drawers"),
    (7, "chair", 3, "chair"),
    (40, "unknown", 40, "misc"),
    (183, "steps", 16, "stairs"),
)
CATEGORY = {raw: index for index, (_, raw, _, _) in enumerate(CATEGORY_ROWS)}

Box = tuple[tuple[float, float, float], tuple[float, float, float]]


@dataclass(frozen=True)
class SceneObject:
    """An annotated object: its O record's id, region, category (-1: none) and box."""

    id: int
    region: int
    category: str | None
    box: Box
    colour: tuple[int, int, int] = (150, 120, 90)
    solid: bool = True  # has triangles of its own in the mesh


FLIGHT_ID = 5
BED_ID = 6
COUCH_ID = 2
REMOVE_ID = 4
UNKNOWN_ID = 9
NO_CATEGORY_ID = 10
OBJECTS = (
    SceneObject(0, 0, "wall", ((7.95, 0.0, 0.0), (8.0, DEPTH, ROOF)), solid=False),
    SceneObject(1, 0, "floor", ((0.0, 0.0, -0.02), (WIDTH, DEPTH, 0.02)), solid=False),
    SceneObject(COUCH_ID, 0, "couch", ((5.0, 1.0, 0.0), (7.0, 2.0, 0.8)), (90, 60, 140)),
    SceneObject(3, 0, "table", ((3.0, 3.0, 0.0), (4.0, 4.0, 0.75)), (160, 110, 60)),
    SceneObject(REMOVE_ID, 0, "remove", ((6.0, 5.0, 0.0), (6.5, 5.5, 0.5)), (200, 200, 200)),
    SceneObject(
        FLIGHT_ID, 1, "steps", ((-0.01, FOOT_Y - 0.02, -0.02), (1.21, HEAD_Y + 0.02, UPPER - 0.05))
    ),
    SceneObject(BED_ID, 2, "bed", ((5.5, 2.0, UPPER), (7.5, 4.2, UPPER + 0.6)), (200, 60, 60)),
    SceneObject(7, 2, "nightstand", ((7.3, 4.5, UPPER), (7.8, 5.0, UPPER + 0.5)), (120, 80, 40)),
    SceneObject(8, 2, "chair", ((2.5, 2.0, UPPER), (3.0, 2.5, UPPER + 0.8)), (60, 120, 60)),
    SceneObject(UNKNOWN_ID, 2, "unknown", ((3.0, 5.5, UPPER), (3.5, 6.0, UPPER + 0.5))),
    SceneObject(NO_CATEGORY_ID, 0, None, ((2.0, 5.5, 0.0), (2.4, 5.9, 0.4)), (90, 90, 90)),
)
# Regions: (index, level, label letter, floor polygon (x, y), floor z, height).
REGIONS = (
    (
        0,
        0,
        "l",
        (
            (0.0, 0.0),
            (WIDTH, 0.0),
            (WIDTH, DEPTH),
            (0.0, DEPTH),
            (0.0, HEAD_Y),
            (1.3, HEAD_Y),
            (1.3, FOOT_Y),
            (0.0, FOOT_Y),
        ),
        0.0,
        UPPER - 0.1,
    ),
    (1, 0, "s", ((0.0, 0.0), (1.2, 0.0), (1.2, HEAD_Y), (0.0, HEAD_Y)), 0.0, UPPER),
    (2, 1, "b", ((0.0, 0.0), (WIDTH, 0.0), (WIDTH, DEPTH), (0.0, DEPTH)), UPPER, ROOF - UPPER),
)


def to_vlln(x: float, y: float, z: float) -> tuple[float, float, float]:
    """A scan point in vlln's frame (habitat's: x, z, -y)."""
    return (x, z, -y)


def write_scene(root: Path, name: str = "2t7WUuJeko7", flight: bool = True) -> Path:
    """Write ``root/<name>/<name>.glb`` and ``.house``; returns the scene folder. Without
    ``flight`` the stairs are not annotated (their steps are then only walls and floor)."""
    folder = root / name
    folder.mkdir(parents=True, exist_ok=True)
    objects = [o for o in OBJECTS if flight or o.id != FLIGHT_ID]
    (folder / f"{name}.house").write_text(_house_text(objects), encoding="utf-8")
    mesh = trimesh.util.concatenate(_meshes())
    (folder / f"{name}.glb").write_bytes(trimesh.exchange.gltf.export_glb(trimesh.Scene(mesh)))
    return folder


# ------------------------------------------------------------------------------- mesh


def _coloured(mesh: trimesh.Trimesh, colour: tuple[int, int, int]) -> trimesh.Trimesh:
    mesh.visual.vertex_colors = np.tile([*colour, 255], (len(mesh.vertices), 1)).astype(np.uint8)
    return mesh


def _box(
    lo: tuple[float, ...], hi: tuple[float, ...], colour: tuple[int, int, int]
) -> trimesh.Trimesh:
    return _coloured(trimesh.creation.box(bounds=np.array([lo, hi], float)), colour)


def _quad(
    corners: list[tuple[float, float, float]], colour: tuple[int, int, int]
) -> trimesh.Trimesh:
    """A flat quad, counter-clockwise as seen from the side its normal faces."""
    return _coloured(
        trimesh.Trimesh(
            vertices=np.array(corners, float), faces=[[0, 1, 2], [0, 2, 3]], process=False
        ),
        colour,
    )


def _level_rect(
    x0: float, y0: float, x1: float, y1: float, z: float, up: bool, colour: tuple[int, int, int]
) -> trimesh.Trimesh:
    corners = [(x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)]
    return _quad(corners if up else corners[::-1], colour)


def _meshes() -> list[trimesh.Trimesh]:
    wood, plaster, tiles = (150, 110, 70), (225, 222, 215), (170, 160, 150)
    x0, x1 = FLIGHT_X
    # Floors and ceilings: the footprint less the stairwell (x0..x1, FOOT_Y..HEAD_Y).
    pieces = [(0.0, 0.0, WIDTH, FOOT_Y), (0.0, HEAD_Y, WIDTH, DEPTH), (x1, FOOT_Y, WIDTH, HEAD_Y)]
    meshes = [_level_rect(*p, 0.0, True, tiles) for p in pieces]
    meshes += [_level_rect(*p, UPPER, True, tiles) for p in pieces]
    meshes += [_level_rect(*p, UPPER - 0.1, False, plaster) for p in pieces]
    meshes.append(_level_rect(0.0, 0.0, WIDTH, DEPTH, ROOF, False, plaster))
    # Outer walls, the stairwell's side wall, the wall under its head and above its foot.
    meshes += [
        _box((-0.1, 0.0, 0.0), (0.0, DEPTH, ROOF), plaster),
        _box((WIDTH, 0.0, 0.0), (WIDTH + 0.1, DEPTH, ROOF), plaster),
        _box((0.0, -0.1, 0.0), (WIDTH, 0.0, ROOF), plaster),
        _box((0.0, DEPTH, 0.0), (WIDTH, DEPTH + 0.1, ROOF), plaster),
        _box((x1, FOOT_Y, 0.0), (x1 + 0.1, HEAD_Y, ROOF), plaster),
        _box((x0, HEAD_Y, 0.0), (x1, HEAD_Y + 0.1, UPPER - RISE), plaster),
        _box((x0, FOOT_Y - 0.1, UPPER), (x1, FOOT_Y, ROOF), plaster),
    ]
    # The flight: a riser then a tread per step; the last riser reaches the upper floor.
    for k in range(RISES):
        y, z = FOOT_Y + k * TREAD, k * RISE
        meshes.append(_quad([(x0, y, z), (x1, y, z), (x1, y, z + RISE), (x0, y, z + RISE)], wood))
        if k < RISES - 1:
            meshes.append(_level_rect(x0, y, x1, y + TREAD, z + RISE, True, wood))
    for obj in OBJECTS:
        if obj.solid and obj.id != FLIGHT_ID:
            meshes.append(_box(obj.box[0], obj.box[1], obj.colour))
    return meshes


# ------------------------------------------------------------------------------- .house


def _n(value: float) -> str:
    """A number as a C++ stream writes it (6 significant digits)."""
    return f"{value:.6g}"


def _ns(values: tuple[float, ...] | list[float]) -> str:
    return " ".join(_n(v) for v in values)


def _house_text(objects: list[SceneObject]) -> str:
    lo, hi = (-0.1, -0.1, 0.0), (WIDTH + 0.1, DEPTH + 0.1, ROOF)
    vertices = sum(len(region[3]) for region in REGIONS)
    panoramas = [(0, 0, (4.0, 5.5, 1.5)), (1, 2, (4.0, 5.5, UPPER + 1.5))]
    counts = (
        len(panoramas), len(panoramas), vertices, len(REGIONS), len(objects), len(objects),
        len(CATEGORY_ROWS), len(REGIONS), 0, 2,
    )  # fmt: skip
    lines = [
        "ASCII 1.1",
        f"H  -  -  {' '.join(str(c) for c in counts)}  0 0 0 0 0  {_ns(lo)}  {_ns(hi)}  0 0 0 0 0",
    ]
    for level, z in ((0, 0.0), (1, UPPER)):
        top = UPPER if level == 0 else ROOF
        lines.append(
            f"L  {level}  0  1  {_ns((4.0, 3.5, z))}  {_ns((lo[0], lo[1], z))}  "
            f"{_ns((hi[0], hi[1], top))}  0 0 0 0 0"
        )
    for index, level, label, polygon, z, height in REGIONS:
        xs, ys = [p[0] for p in polygon], [p[1] for p in polygon]
        centre = (sum(xs) / len(xs), sum(ys) / len(ys), z)
        rlo, rhi = (min(xs), min(ys), z), (max(xs), max(ys), z + height)
        lines.append(
            f"R  {index} {level}  0 0  {label}  {_ns(centre)}  {_ns(rlo)}  {_ns(rhi)}  "
            f"{_n(height)}  0 0 0 0"
        )
    for index, _, _, polygon, z, _ in REGIONS:
        xs, ys = [p[0] for p in polygon], [p[1] for p in polygon]
        centre = (sum(xs) / len(xs), sum(ys) / len(ys), z)
        lines.append(
            f"S  {index} {index}  0  F  {_ns(centre)}  0 0 1  {_ns((min(xs), min(ys), z))}  "
            f"{_ns((max(xs), max(ys), z))}  0 0 0 0 0"
        )
    vertex = 0
    for index, _, _, polygon, z, _ in REGIONS:
        for x, y in polygon:
            lines.append(f"V  {vertex} {index}  F  {_ns((x, y, z))}  0 0 1  0 0 0")
            vertex += 1
    for index, region, position in panoramas:
        lines.append(f"P  {index:032x}  {index} {region}  0  {_ns(position)}  0 0 0 0 0")
    for index, _, (px, py, pz) in panoramas:
        # World-to-camera: identity rotation, so the translation is minus the centre.
        extrinsics = [1, 0, 0, -px, 0, 1, 0, -py, 0, 0, 1, -pz, 0, 0, 0, 1]
        intrinsics = [1075.1, 0, 629.7, 0, 1075.1, 505.1, 0, 0, 1]
        lines.append(
            f"I  {index} {index}  {index:032x}  0 0  {_ns(extrinsics)}  "
            f"{_ns(intrinsics)}  1280 1024  {_ns((px, py, pz))}  0 0 0 0 0"
        )
    for index, (mapping, raw, group, group_name) in enumerate(CATEGORY_ROWS):
        lines.append(f"C  {index}  {mapping} {raw}  {group} {group_name}  0 0 0 0 0")
    for obj in objects:
        (bx0, by0, bz0), (bx1, by1, bz1) = obj.box
        centre = ((bx0 + bx1) / 2, (by0 + by1) / 2, (bz0 + bz1) / 2)
        # Axis 0 vertical and axis 1 along y, as in some real records: radii z, y, x.
        radii = ((bz1 - bz0) / 2, (by1 - by0) / 2, (bx1 - bx0) / 2)
        category = -1 if obj.category is None else CATEGORY[obj.category]
        lines.append(
            f"O  {obj.id} {obj.region} {category}  {_ns(centre)}  0 0 1  0 1 -0  "
            f"{_ns(radii)}  0 0 0 0 0 0 0 0"
        )
    for obj in objects:
        (bx0, by0, bz0), (bx1, by1, bz1) = obj.box
        centre = ((bx0 + bx1) / 2, (by0 + by1) / 2, (bz0 + bz1) / 2)
        lines.append(
            f"E  {obj.id} {obj.id} {obj.id + 1} 0.5  {_ns(centre)}  {_ns((bx0, by0, bz0))}  "
            f"{_ns((bx1, by1, bz1))}  0 0 0 0 0"
        )
    return "\n".join(lines) + "\n"
