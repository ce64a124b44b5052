"""The fixed shell of a house: floors, ceilings, walls, door openings with their frames.

Walls are built line by line: every straight line that carries room edges is cut into pieces
where the room on either side changes or a door opens, so each wall face takes the colour of
the room it faces and door openings stay clear from the floor to the lintel. Pieces that end
a wall line are lengthened by half the wall thickness so that corners close without gaps.
Faces nobody can see (wall tops under the ceiling, ends buried in other walls) are not built.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass
from itertools import pairwise

import numpy as np

from vlln.world.generator.doors import door_along, door_wall_coord
from vlln.world.generator.layout import FloorPlan
from vlln.world.generator.params import HouseParameters
from vlln.world.generator.rect import Rect
from vlln.world.materials import COLORS, Rgb, material_index
from vlln.world.mesh import Mesh, MeshBuilder
from vlln.world.model import Door, StructureId

DOOR_HEIGHT = 2.1  # top of a door opening, m
JAMB_WIDTH = 0.05  # door-frame strips beside an opening (outside the clear width), m
JAMB_PROTRUSION = 0.01  # how far a frame stands out of the wall face, m

# Floor finishes per room type: (material, colour names to draw from).
FLOOR_FINISHES: dict[str, tuple[tuple[str, tuple[str, ...]], ...]] = {
    "living room": (("wood", ("brown", "beige", "dark brown")), ("carpet", ("beige", "gray"))),
    "bedroom": (("wood", ("brown", "beige")), ("carpet", ("beige", "light gray", "navy"))),
    "kitchen": (("tile", ("white", "light gray", "beige")),),
    "dining room": (("wood", ("brown", "beige", "dark brown")),),
    "bathroom": (("tile", ("white", "light gray", "light blue")),),
    "toilet": (("tile", ("white", "light gray", "beige")),),
    "study": (("wood", ("brown", "dark brown")), ("carpet", ("gray", "dark green"))),
    "corridor": (("wood", ("brown", "beige")), ("tile", ("light gray", "beige"))),
    "storage room": (("plain", ("gray", "light gray")),),
    "gym": (("carpet", ("dark gray", "gray")), ("wood", ("beige",))),
}
DEFAULT_FLOOR = (("wood", ("brown",)),)
WALL_COLORS = ("white", "cream", "beige", "light blue", "light gray", "pink", "light gray")
TILED_WALL_ROOMS = ("kitchen", "bathroom", "toilet")
FRAME_COLORS = ("white", "brown", "dark brown", "beige")


@dataclass(frozen=True)
class _Finish:
    color: Rgb
    material: int


def build_structure(plan: FloorPlan, params: HouseParameters, rng: np.random.Generator) -> Mesh:
    """Floors, ceilings, walls and door frames of a floor plan as one mesh."""
    rects = plan.rects
    floors = MeshBuilder()
    ceilings = MeshBuilder()
    wall_finish: list[_Finish] = []
    for room, rect in zip(plan.rooms, rects, strict=True):
        options = FLOOR_FINISHES.get(room.type, DEFAULT_FLOOR)
        material, colors = options[int(rng.integers(len(options)))]
        color = COLORS[colors[int(rng.integers(len(colors)))]]
        floors.quad(
            (rect.x0, 0.0, rect.z0),
            (0.0, 0.0, rect.depth),
            (rect.width, 0.0, 0.0),
            color,
            material_index(material),
        )
        ceilings.quad(
            (rect.x0, params.ceiling_height, rect.z0),
            (rect.width, 0.0, 0.0),
            (0.0, 0.0, rect.depth),
            COLORS["white"],
            material_index("plain"),
        )
        wall_color = _pastel(COLORS[WALL_COLORS[int(rng.integers(len(WALL_COLORS)))]])
        wall_material = "tile" if room.type in TILED_WALL_ROOMS else "plain"
        wall_finish.append(_Finish(wall_color, material_index(wall_material)))
    frame = _Finish(
        COLORS[FRAME_COLORS[int(rng.integers(len(FRAME_COLORS)))]], material_index("wood")
    )
    walls = MeshBuilder()
    frames = MeshBuilder()
    outside = _Finish(COLORS["white"], material_index("plain"))
    for (axis, coord), edges in sorted(_wall_lines(rects).items()):
        doors = [d for d in plan.doors if d.axis == axis and door_wall_coord(d) == coord]
        _build_line(axis, coord, edges, doors, wall_finish, outside, frame, params, walls, frames)
    return Mesh.concatenate(
        [
            floors.build().with_instance_id(StructureId.FLOOR),
            ceilings.build().with_instance_id(StructureId.CEILING),
            walls.build().with_instance_id(StructureId.WALL),
            frames.build().with_instance_id(StructureId.DOOR_FRAME),
        ]
    )


def _pastel(color: Rgb) -> Rgb:
    r, g, b = color
    return (0.7 * r + 0.3, 0.7 * g + 0.3, 0.7 * b + 0.3)


# An edge on a wall line: (start, end, room id, side) with side -1 when the room lies on the
# negative side of the line (its far edge is the line) and +1 when it lies on the positive side.
_Edge = tuple[float, float, int, int]


def _wall_lines(rects: list[Rect]) -> dict[tuple[str, float], list[_Edge]]:
    lines: dict[tuple[str, float], list[_Edge]] = defaultdict(list)
    for i, r in enumerate(rects):
        lines[("z", r.x0)].append((r.z0, r.z1, i, +1))
        lines[("z", r.x1)].append((r.z0, r.z1, i, -1))
        lines[("x", r.z0)].append((r.x0, r.x1, i, +1))
        lines[("x", r.z1)].append((r.x0, r.x1, i, -1))
    return lines


def _build_line(
    axis: str,
    coord: float,
    edges: list[_Edge],
    doors: list[Door],
    finish: list[_Finish],
    outside: _Finish,
    frame: _Finish,
    params: HouseParameters,
    walls: MeshBuilder,
    frames: MeshBuilder,
) -> None:
    """Wall pieces, lintels and jambs along one wall line."""
    openings = [(door_along(d) - d.width / 2.0, door_along(d) + d.width / 2.0) for d in doors]
    cuts = sorted({p for e in edges for p in e[:2]} | {p for o in openings for p in o})
    # Elementary stretches between cuts, labelled by (room on - side, room on + side, door?).
    stretches: list[tuple[float, float, int, int, bool]] = []
    for a, b in pairwise(cuts):
        mid = (a + b) / 2.0
        minus = next((e[2] for e in edges if e[3] < 0 and e[0] <= mid <= e[1]), -1)
        plus = next((e[2] for e in edges if e[3] > 0 and e[0] <= mid <= e[1]), -1)
        is_door = any(o[0] <= mid <= o[1] for o in openings)
        if minus >= 0 or plus >= 0:
            stretches.append((a, b, minus, plus, is_door))
    merged: list[list[float | int | bool]] = []
    for s in stretches:
        if merged and merged[-1][1] == s[0] and tuple(merged[-1][2:]) == s[2:]:
            merged[-1][1] = s[1]
        else:
            merged.append(list(s))
    half = params.wall_thickness / 2.0
    ends = {float(m[0]) for m in merged} ^ {float(m[1]) for m in merged}  # free ends
    height = params.ceiling_height
    for a_, b_, minus_, plus_, is_door_ in merged:
        a, b, minus, plus = float(a_), float(b_), int(minus_), int(plus_)
        face_minus = finish[minus] if minus >= 0 else outside
        face_plus = finish[plus] if plus >= 0 else outside
        if is_door_:
            # The lintel above the opening, then the frame: two jambs and a header.
            _wall_box(axis, coord, a, b, DOOR_HEIGHT, height, half, face_minus, face_plus, frames)
            frame_half = half + JAMB_PROTRUSION
            for lo, hi in ((a - JAMB_WIDTH, a), (b, b + JAMB_WIDTH)):
                _frame_box(
                    axis, coord, lo, hi, 0.0, DOOR_HEIGHT + JAMB_WIDTH, frame_half, frame, frames
                )
            _frame_box(
                axis, coord, a, b, DOOR_HEIGHT, DOOR_HEIGHT + JAMB_WIDTH, frame_half, frame, frames
            )
            continue
        lo = a - half if a in ends else a
        hi = b + half if b in ends else b
        _wall_box(axis, coord, lo, hi, 0.0, height, half, face_minus, face_plus, walls)


def _wall_box(
    axis: str,
    coord: float,
    lo: float,
    hi: float,
    bottom: float,
    top: float,
    half: float,
    face_minus: _Finish,
    face_plus: _Finish,
    builder: MeshBuilder,
) -> None:
    """The two long faces of a wall piece."""
    length, height = hi - lo, top - bottom
    if axis == "x":  # constant z; faces look along -z and +z
        builder.quad(
            (lo, bottom, coord - half),
            (0.0, height, 0.0),
            (length, 0.0, 0.0),
            face_minus.color,
            face_minus.material,
        )
        builder.quad(
            (lo, bottom, coord + half),
            (length, 0.0, 0.0),
            (0.0, height, 0.0),
            face_plus.color,
            face_plus.material,
        )
    else:  # constant x; faces look along -x and +x
        builder.quad(
            (coord - half, bottom, lo),
            (0.0, 0.0, length),
            (0.0, height, 0.0),
            face_minus.color,
            face_minus.material,
        )
        builder.quad(
            (coord + half, bottom, lo),
            (0.0, height, 0.0),
            (0.0, 0.0, length),
            face_plus.color,
            face_plus.material,
        )


def _frame_box(
    axis: str,
    coord: float,
    lo: float,
    hi: float,
    bottom: float,
    top: float,
    half: float,
    frame: _Finish,
    builder: MeshBuilder,
) -> None:
    """A door-frame strip: a box ``[lo, hi]`` along the wall, standing out of both faces."""
    centre_along, length = (lo + hi) / 2.0, hi - lo
    centre_y, height = (bottom + top) / 2.0, top - bottom
    if axis == "x":
        builder.box(
            (centre_along, centre_y, coord),
            (length, height, 2 * half),
            frame.color,
            frame.material,
            faces="+x-x-y+z-z",
        )
    else:
        builder.box(
            (coord, centre_y, centre_along),
            (2 * half, height, length),
            frame.color,
            frame.material,
            faces="+z-z-y+x-x",
        )
