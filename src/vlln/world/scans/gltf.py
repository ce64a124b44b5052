"""Reading and writing the binary glTF (``.glb``) meshes of scanned scenes, with trimesh.

Scans are stored z-up (Matterport's frame, which habitat turns upright with its scene-dataset
configs: up +z, front -y); vlln's frame is y-up (:mod:`vlln.world.frame`), so a scan point
``(x, y, z)`` is ``(x, z, -y)`` here. Colours come from the vertex colours (``COLOR_0``,
linear) or from the material's base colour and texture, sampled at each vertex (textures are
sRGB, so they are turned linear). Basis Universal textures (HM3D's ``.basis.glb``) cannot be
decoded here: reading one is a :class:`DataFormatError` that names the file to use instead.
"""

from __future__ import annotations

import struct
from pathlib import Path
from typing import Any

import numpy as np
import trimesh
from numpy.typing import NDArray

from vlln.errors import DataFormatError
from vlln.files import ReadCap, parse_json, write_bytes_atomic

FloatArray = NDArray[np.float64]

# A scan's glTF JSON (nodes, accessors, materials) is kilobytes; the mesh is in the binary chunk.
MAX_GLTF_JSON_BYTES = 16 << 20
# Matterport3D's and HM3D's glb meshes run to a few hundred MB; the loader holds the whole file,
# then its arrays, so a larger file is refused before it is read.
SCAN_MESH_CAP = ReadCap("a scan mesh (.glb)", 1024, "VLLN_MAX_SCAN_MESH_MB")


def to_scan_frame(points: NDArray[np.floating]) -> FloatArray:
    """``(x, y, z)`` -> ``(x, -z, y)``, row by row."""
    out = np.asarray(points, np.float64)[:, [0, 2, 1]]
    out[:, 1] *= -1.0
    return out


def from_scan_frame(points: NDArray[np.floating]) -> FloatArray:
    """``(x, y, z)`` -> ``(x, z, -y)``, row by row."""
    out = np.asarray(points, np.float64)[:, [0, 2, 1]]
    out[:, 2] *= -1.0
    return out


def _gltf_json(path: Path) -> dict[str, Any]:
    """The JSON chunk of a ``.glb`` (header: magic, version, length; then the JSON chunk's
    length and type, and the chunk), untrusted JSON of at most :data:`MAX_GLTF_JSON_BYTES`."""
    with path.open("rb") as handle:
        head = handle.read(20)
        if len(head) < 20 or head[:4] != b"glTF":
            raise DataFormatError(f"{path} is not a binary glTF (.glb) file")
        (length,) = struct.unpack("<I", head[12:16])
        if length > MAX_GLTF_JSON_BYTES:
            raise DataFormatError(
                f"{path}: its JSON chunk declares {length} bytes, over the cap of "
                f"{MAX_GLTF_JSON_BYTES >> 20} MiB; give the scan's own .glb"
            )
        try:
            data = parse_json(handle.read(length))
        except DataFormatError as err:
            raise DataFormatError(f"{path}: its glTF JSON chunk cannot be read: {err}") from None
    if not isinstance(data, dict):
        raise DataFormatError(f"{path}: its glTF JSON chunk is not an object")
    return data


def check_decodable(path: Path) -> None:
    """Refuse texture encodings we cannot decode, naming the file to use instead."""
    data = _gltf_json(path)
    used = {str(name) for name in data.get("extensionsUsed") or []}
    images = data.get("images") or []
    ktx2 = any(isinstance(i, dict) and i.get("mimeType") == "image/ktx2" for i in images)
    if "KHR_texture_basisu" in used or ktx2:
        plain = path.name.replace(".basis.glb", ".glb")
        hint = f"use {plain} from the dataset's plain-texture 'glb' download instead"
        if plain == path.name:
            hint = "use the dataset's plain-texture (JPEG/PNG) .glb instead"
        raise DataFormatError(
            f"{path} has Basis Universal (KTX2) textures, which vlln cannot decode; {hint}"
        )


def read_glb(path: Path) -> tuple[FloatArray, FloatArray]:
    """Triangles ``(n, 3, 3)`` in vlln's frame and their vertex colours ``(n, 3, 3)``, linear."""
    if not path.is_file():
        raise DataFormatError(f"{path} does not exist")
    SCAN_MESH_CAP.check_size(path)
    check_decodable(path)
    try:
        scene = trimesh.load(str(path), file_type="glb", force="scene", process=False)
    except Exception as err:  # trimesh raises many types for a broken file
        raise DataFormatError(f"{path} cannot be read as a glTF mesh: {err}") from None
    triangles: list[FloatArray] = []
    colours: list[FloatArray] = []
    meshes = scene.dump(concatenate=False) if isinstance(scene, trimesh.Scene) else [scene]
    for mesh in meshes:
        if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
            continue
        faces = np.asarray(mesh.faces)
        triangles.append(from_scan_frame(np.asarray(mesh.vertices)[faces].reshape(-1, 3)))
        colours.append(_vertex_colours(mesh)[faces].reshape(-1, 3))
    if not triangles:
        raise DataFormatError(f"{path} holds no triangles")
    if not all(np.isfinite(part).all() for part in triangles):
        raise DataFormatError(
            f"{path} has vertices that are not finite numbers (NaN or infinity); "
            "give the scan's own .glb"
        )
    return (
        np.concatenate(triangles).reshape(-1, 3, 3),
        np.concatenate(colours).reshape(-1, 3, 3),
    )


def _vertex_colours(mesh: trimesh.Trimesh) -> FloatArray:
    visual = mesh.visual
    if isinstance(visual, trimesh.visual.texture.TextureVisuals):
        srgb = np.asarray(visual.to_color().vertex_colors, np.float64)[:, :3] / 255.0
        return np.power(srgb, 2.2)
    colours = getattr(visual, "vertex_colors", None)
    if colours is None:
        return np.full((len(mesh.vertices), 3), 0.6)
    rgb: FloatArray = np.asarray(colours, np.float64)[:, :3] / 255.0
    return rgb


def write_glb(path: Path, triangles: NDArray[np.floating], colours: NDArray[np.floating]) -> None:
    """Triangles ``(n, 3, 3)`` in vlln's frame with linear vertex colours, as a z-up ``.glb``."""
    vertices = to_scan_frame(np.asarray(triangles).reshape(-1, 3))
    faces = np.arange(len(vertices)).reshape(-1, 3)
    rgba = np.concatenate([np.asarray(colours).reshape(-1, 3), np.ones((len(vertices), 1))], axis=1)
    mesh = trimesh.Trimesh(
        vertices=vertices,
        faces=faces,
        vertex_colors=np.round(np.clip(rgba, 0.0, 1.0) * 255).astype(np.uint8),
        process=False,
    )
    write_bytes_atomic(path, trimesh.exchange.gltf.export_glb(trimesh.Scene(mesh)))
