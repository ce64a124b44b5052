"""A contact sheet of the catalogue: every category rendered at the agent's 640x480.

Each category is built in one style, stood on a floor (hung on a wall, or from a ceiling, as
the generator places it) and seen by the real renderer from a three-quarter view that frames
its bounding sphere, so what the sheet shows is what an agent sees. The sheet is for people to
check that each model is recognisable; the per-category images are kept next to it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from PIL import Image, ImageDraw

from vlln.files import check_output_folder, writing
from vlln.sim.camera import CameraSpec
from vlln.sim.renderer import Renderer
from vlln.viz.frames import save_png
from vlln.world.catalogue.base import Category, Placement, Style
from vlln.world.catalogue.registry import Catalogue
from vlln.world.materials import color_rgb, material_index
from vlln.world.mesh import Mesh, MeshBuilder
from vlln.world.model import StructureId

VIEW_YAW = math.radians(28.0)  # turned off the front, so depth shows
VIEW_ELEVATION = math.radians(18.0)  # looking slightly down on the model
CEILING = 2.6  # m; ceiling models hang from here
MARGIN = 1.15  # the bounding sphere fills this fraction less of the view
THUMB = (213, 160)  # a third of 640x480
LABEL_HEIGHT = 16
COLUMNS = 8


@dataclass(frozen=True)
class CategoryView:
    """One rendered category: its name, the style shown and the image."""

    name: str
    fine_category: str
    rgb: NDArray[np.uint8]
    object_pixels: int  # pixels of the model in the instance-id image


def sheet_style(category: Category) -> Style:
    """The style a category is shown in: its first shape, colour and material."""
    return Style(category.colors[0], category.materials[0], next(iter(category.shapes)))


def render_category(category: Category, spec: CameraSpec | None = None) -> CategoryView:
    """The category's model in its usual setting, seen by the renderer."""
    spec = spec if spec is not None else CameraSpec()
    style = sheet_style(category)
    model = category.build(style, np.random.default_rng(0)).mesh.with_instance_id(1)
    lift = 0.0
    if category.placement is Placement.WALL_MOUNTED:
        lift = category.wall_height
    elif category.placement is Placement.CEILING:
        lift = CEILING - float(model.bounds()[1][1])
    model = model.transformed(0.0, (0.0, lift, 0.0))
    lo, hi = (b.astype(np.float64) for b in model.bounds())
    centre = (lo + hi) / 2.0
    radius = max(float(np.linalg.norm(hi - lo)) / 2.0, 0.05)
    scene = Mesh.concatenate([model, _setting(category, lo, hi)])
    vfov = 2.0 * math.atan(math.tan(math.radians(spec.hfov_deg) / 2.0) * spec.height / spec.width)
    distance = MARGIN * radius / math.sin(vfov / 2.0)
    look_up = category.placement is Placement.CEILING
    elevation = -VIEW_ELEVATION if look_up else VIEW_ELEVATION
    across = distance * math.cos(elevation)
    eye_x = centre[0] + across * math.sin(VIEW_YAW)
    eye_z = centre[2] + across * math.cos(VIEW_YAW)
    eye_y = centre[1] + distance * math.sin(elevation)
    camera = CameraSpec(
        width=spec.width,
        height=spec.height,
        hfov_deg=spec.hfov_deg,
        height_m=max(eye_y, 0.0),
        near=min(spec.near, distance / 20.0),
        far=spec.far,
        max_depth=spec.max_depth,
    )
    with Renderer(scene, camera, cull_back_faces=False) as renderer:
        frame = renderer.render((eye_x, eye_y - camera.height_m, eye_z), VIEW_YAW, -elevation)
    pixels = int(np.count_nonzero(frame.instance_ids == 1))
    return CategoryView(category.name, category.shapes[style.shape], frame.rgb.copy(), pixels)


def _setting(category: Category, lo: NDArray[np.float64], hi: NDArray[np.float64]) -> Mesh:
    """A floor under the model, a wall behind it and, for ceiling models, the ceiling."""
    b = MeshBuilder()
    plain = material_index("plain")
    radius = float(np.linalg.norm(hi - lo)) / 2.0
    size = 8.0 * radius + 2.0
    b.box((0.0, -0.01, 0.0), (size, 0.02, size), color_rgb("beige"), plain)
    gap = 0.0 if category.placement is Placement.WALL_MOUNTED else 0.3
    wall_z = min(float(lo[2]), 0.0) - gap - 0.01
    top = float(hi[1]) + 2.0 * radius + 0.5
    b.box((0.0, top / 2.0, wall_z), (size, top, 0.02), color_rgb("cream"), plain)
    if category.placement is Placement.CEILING:
        b.box((0.0, CEILING + 0.01, 0.0), (size, 0.02, size), color_rgb("white"), plain)
    return b.build().with_instance_id(int(StructureId.FLOOR))


def write_catalogue_sheet(catalogue: Catalogue, out: Path, columns: int = COLUMNS) -> Path:
    """Render every category to ``out/<name>.png`` and tile them, labelled, into
    ``out/catalogue.png``; returns the sheet's path. Each picture is written as soon as it is
    rendered, so a full disk stops the command at once."""
    check_output_folder(out)
    views: list[CategoryView] = []
    for category in catalogue:
        view = render_category(category)
        save_png(view.rgb, out / f"{view.name.replace(' ', '_')}.png")
        views.append(view)
    rows = math.ceil(len(views) / columns)
    cell_w, cell_h = THUMB[0], THUMB[1] + LABEL_HEIGHT
    sheet = Image.new("RGB", (columns * cell_w, rows * cell_h), "white")
    draw = ImageDraw.Draw(sheet)
    for k, view in enumerate(views):
        x, y = (k % columns) * cell_w, (k // columns) * cell_h
        thumb = Image.fromarray(view.rgb).resize(THUMB, Image.Resampling.LANCZOS)
        sheet.paste(thumb, (x, y + LABEL_HEIGHT))
        label = f"{view.name} ({view.fine_category})"
        if draw.textlength(label) > cell_w - 8:  # too long for its cell: the name alone
            label = view.name
        draw.text((x + 4, y + 2), label, fill="black")
    path = out / "catalogue.png"
    with writing(path):
        sheet.save(path)
    return path
