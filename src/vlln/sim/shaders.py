"""GLSL sources of the renderer, the vertex layout they read and the material table.

Kept apart from :mod:`vlln.sim.renderer` so a benchmark can draw exactly the same triangles
with a bare moderngl loop and measure how much the Python wrapper costs.

Mesh colours are linear RGB. The vertex shader looks up the material, lights the vertex
(hemisphere ambient from the sky above and the ground below, a fixed key light, a weak
headlight, highlights, a fake mirror reflection, distance falloff) and encodes the result to
sRGB. The fragment shader applies the material's procedural texture and writes three targets
in one pass: sRGB colour, z-depth in metres (from ``gl_FragCoord.w``) and the instance id.

Materials share ONE procedural texture and lighting model whose parameters come from a
per-material table (:data:`MATERIAL_LOOKS`): warped stripes (wood grain, brushed metal,
marble veins, leaf edges), two octaves of cell noise (leather grain, carpet pile, per-tile
shade, leaves), a grid (tile grout, fabric weave) and glossy, metallic and sheen terms. On a
CPU rasteriser a branch per material would be paid by every pixel, so there is no branch; a
texture fades to its mean colour where its period falls below a few pixels, so distant
surfaces do not shimmer with moiré.
"""

from __future__ import annotations

from typing import cast

import moderngl
import numpy as np
from pydantic import Field

from vlln.config import Positive, settings_dataclass
from vlln.errors import ConfigError
from vlln.sim.camera import CameraSpec, Position
from vlln.world.materials import MATERIALS
from vlln.world.mesh import Mesh

# One interleaved record per vertex: position, normal, uv, colour, material, instance id.
VERTEX_FORMAT = "3f 3f 2f 3f 1i 1i"
VERTEX_ATTRIBUTES = ("in_position", "in_normal", "in_uv", "in_color", "in_material", "in_instance")
VERTEX_DTYPE = np.dtype(
    [
        ("position", "<f4", 3),
        ("normal", "<f4", 3),
        ("uv", "<f4", 2),
        ("color", "<f4", 3),
        ("material", "<i4"),
        ("instance", "<i4"),
    ]
)


def interleave_vertices(mesh: Mesh) -> bytes:
    """The mesh as one vertex buffer in :data:`VERTEX_FORMAT` order, grouped by instance.

    Each object's triangles are contiguous (so the renderer can cull and sort whole objects)
    and objects come before the structure (negative ids): a static draw of the buffer lets
    floor and wall pixels hidden behind furniture fail the early depth test instead of being
    shaded and then overdrawn.
    """
    bad = (mesh.materials < 0) | (mesh.materials >= len(MATERIALS))
    if bad.any():
        raise ConfigError(
            f"mesh material index {int(mesh.materials[bad][0])} is out of range; use an index "
            f"into vlln.world.materials.MATERIALS (0..{len(MATERIALS) - 1})"
        )
    records = np.empty(len(mesh.positions), VERTEX_DTYPE)
    records["position"] = mesh.positions
    records["normal"] = mesh.normals
    records["uv"] = mesh.uvs
    records["color"] = mesh.colors
    records["material"] = mesh.materials
    records["instance"] = mesh.instance_ids
    triangle_ids = mesh.instance_ids[::3]
    triangle_order = np.lexsort((triangle_ids, triangle_ids < 0))
    vertex_order = (triangle_order[:, None] * 3 + np.arange(3)).ravel()
    return records[vertex_order].tobytes()


@settings_dataclass
class MaterialLook:
    """Parameters of the shared procedural texture and lighting model for one material.

    Frequencies are in cycles per metre along the texture coordinate ``(u, v)``. Texture
    amounts are fractions of the displayed (sRGB) brightness that a pattern removes or varies.
    """

    stripe_cycles: tuple[float, float] = (0.0, 0.0)  # stripes across this direction
    warp_cycles: tuple[float, float] = (0.0, 0.0)  # a wave that bends the stripes
    warp: float = 0.0  # how far the stripes are bent, in stripe periods
    stripe_sharpness: float = Field(default=1.0, ge=1.0)  # 1: soft bands; larger: thin lines
    stripe_amount: float = 0.0  # negative: light stripes (reflections on glass)
    fine_cells: float = 1.0  # cells per metre of the fine noise
    fine_amount: float = 0.0
    coarse_cells: float = 1.0  # cells per metre of the coarse noise
    coarse_amount: float = 0.0
    coarse_tint: float = 0.0  # the coarse noise also turns green toward yellow (leaves)
    cell_warp: float = 0.0  # wavy coarse-cell borders instead of squares, in cells
    grid_period: Positive = 1.0  # metres between grid lines
    grid_half_width: float = 0.0  # metres
    grid_amount: float = 0.0
    diffuse: float = 1.0  # scale of the base colour
    whiten: float = 0.0  # mix of the base colour toward white (glaze)
    specular: float = 0.0  # strength of the light highlights
    shininess: float = 16.0  # Blinn-Phong exponent: larger is a smaller, sharper highlight
    gloss: float = 0.0  # mirror-like reflection of a bright ceiling and a dark floor
    metallic: float = 0.0  # highlights and reflections take the base colour
    sheen: float = 0.0  # extra light at grazing angles (fabric pile)

    def packed(self) -> list[float]:
        """24 floats (6 vec4) in the order the vertex shader reads them."""
        period = self.grid_period
        return [
            *self.stripe_cycles, *self.warp_cycles,
            self.warp, self.stripe_sharpness, self.stripe_amount, self.coarse_tint,
            self.fine_cells, self.fine_amount, self.coarse_cells, self.coarse_amount,
            1.0 / period, self.cell_warp, self.grid_half_width / period, self.grid_amount,
            self.diffuse, self.whiten, self.metallic, self.sheen,
            self.specular, self.shininess, self.gloss, 0.0,
        ]  # fmt: skip


# fmt: off
MATERIAL_LOOKS: dict[str, MaterialLook] = {
    "plain": MaterialLook(),
    "wood": MaterialLook(
        stripe_cycles=(0.0, 24.0), warp_cycles=(0.35, 0.9), warp=1.4, stripe_sharpness=1.6,
        stripe_amount=0.30, fine_cells=160.0, fine_amount=0.08, specular=0.12,
    ),
    "fabric": MaterialLook(
        grid_period=0.012, grid_half_width=0.0022, grid_amount=0.22, fine_cells=250.0,
        fine_amount=0.08, sheen=0.45, diffuse=0.95,
    ),
    "metal": MaterialLook(
        stripe_cycles=(0.0, 120.0), warp_cycles=(0.0, 7.0), warp=0.15, stripe_amount=0.07,
        fine_cells=500.0, fine_amount=0.14, diffuse=0.35, specular=1.0, shininess=30.0,
        gloss=0.8, metallic=0.85,
    ),
    "marble": MaterialLook(
        stripe_cycles=(1.1, 0.7), warp_cycles=(1.7, -2.3), warp=0.55, stripe_sharpness=30.0,
        stripe_amount=0.35, coarse_cells=5.0, coarse_amount=0.06, cell_warp=0.8, whiten=0.4,
        specular=0.35, shininess=60.0, gloss=0.3,
    ),
    "leather": MaterialLook(
        fine_cells=300.0, fine_amount=0.14, specular=0.3, shininess=10.0, gloss=0.1,
    ),
    "glass": MaterialLook(
        stripe_cycles=(0.9, 0.9), stripe_sharpness=6.0, stripe_amount=-0.2, diffuse=0.4,
        specular=1.2, shininess=120.0, gloss=1.0,
    ),
    "plastic": MaterialLook(specular=0.6, shininess=48.0, gloss=0.25),
    "ceramic": MaterialLook(whiten=0.3, specular=0.8, shininess=90.0, gloss=0.4),
    "tile": MaterialLook(
        coarse_cells=1.0 / 0.3, coarse_amount=0.10, grid_period=0.3, grid_half_width=0.002,
        grid_amount=0.4, specular=0.25, shininess=40.0, gloss=0.1,
    ),
    "carpet": MaterialLook(fine_cells=250.0, fine_amount=0.30, sheen=0.15),
    "foliage": MaterialLook(
        stripe_cycles=(9.0, 6.0), warp_cycles=(7.0, -11.0), warp=0.5, stripe_sharpness=3.0,
        stripe_amount=0.35, fine_cells=45.0, fine_amount=0.45, coarse_cells=14.0,
        coarse_amount=0.35, cell_warp=0.9, coarse_tint=0.3, specular=0.08,
    ),
}
# fmt: on

N_MATERIALS = len(MATERIALS)
# Unit direction toward the key light, world frame: from above, right and behind yaw 0.
KEY_LIGHT_DIRECTION = (0.3841, 0.8536, 0.3521)


def program_uniform(program: moderngl.Program, name: str) -> moderngl.Uniform:
    """A uniform of the program (moderngl's lookup also returns attributes and blocks)."""
    return cast(moderngl.Uniform, program[name])


def upload_static_uniforms(program: moderngl.Program, spec: CameraSpec) -> None:
    """Uniforms that change only with the camera spec: the material table and the intrinsics."""
    table = [x for name in MATERIALS for x in MATERIAL_LOOKS[name].packed()]
    program_uniform(program, "u_materials").write(np.asarray(table, np.float32).tobytes())
    program_uniform(program, "u_pixel_angle").value = 1.0 / spec.intrinsics().fx
    program_uniform(program, "u_max_depth").value = spec.max_depth


def pose_uniforms(
    spec: CameraSpec, position: Position, yaw: float, tilt: float
) -> dict[str, bytes]:
    """Per-frame uniform values (raw bytes) for a camera pose, keyed by uniform name."""
    view_projection = spec.projection_matrix() @ spec.view_matrix(position, yaw, tilt)
    return {
        # OpenGL reads matrices column-major, hence the transpose.
        "u_view_projection": view_projection.T.astype(np.float32).tobytes(),
        "u_eye": spec.eye(position).astype(np.float32).tobytes(),
    }


VERTEX_SHADER = f"""
#version 330 core
uniform mat4 u_view_projection;
uniform vec3 u_eye;
uniform float u_pixel_angle;  // 1 / fx: radians per pixel at the image centre
uniform vec4 u_materials[{6 * N_MATERIALS}];

in vec3 in_position;
in vec3 in_normal;
in vec2 in_uv;
in vec3 in_color;
in int in_material;
in int in_instance;

out vec2 v_uv;
out vec3 v_lit;  // base colour times the diffuse light, sRGB-encoded
out vec3 v_shine;  // what highlights and reflections add to it, in sRGB
out float v_slant;  // metres of surface under one pixel per metre of depth
flat out vec4 v_waves;  // texture parameters of the material, see MaterialLook.packed
flat out vec4 v_stripes;
flat out vec4 v_cells;
flat out vec4 v_grid;
flat out int v_instance;
invariant gl_Position;  // the id pass (vlln.sim.id_pass) must cover the same pixels

const vec3 KEY_DIRECTION = vec3{KEY_LIGHT_DIRECTION};
const vec3 KEY_COLOR = vec3(0.50, 0.47, 0.42);
const vec3 SKY = vec3(0.44, 0.46, 0.50);
const vec3 GROUND = vec3(0.27, 0.25, 0.23);
const float HEADLIGHT = 0.16;

float sharpen(float x, float k) {{  // Schlick's cheap stand-in for pow(x, k) on [0, 1]
    return x / (k - k * x + x);
}}

vec3 srgb(vec3 linear) {{  // the sRGB transfer curve, clamped to [0, 1]
    vec3 c = clamp(linear, 0.0, 1.0);
    return mix(1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, 12.92 * c, lessThan(c, vec3(0.0031308)));
}}

// Lighting and the material table lookup happen per vertex: the lights are directional and
// the lighting terms smooth, so interpolating them loses little, and a CPU rasteriser runs
// several times fewer vertices than pixels. Texture parameters reach the fragment shader as
// flat values (a per-pixel table lookup is a slow gather there).
void main() {{
    int base = in_material * 6;
    vec4 surface = u_materials[base + 4];  // diffuse, whiten, metallic, sheen
    vec4 shine = u_materials[base + 5];  // specular, shininess, gloss, -
    vec3 to_eye = u_eye - in_position;
    float distance = length(to_eye);
    vec3 view = to_eye / max(distance, 1e-6);
    vec3 n = normalize(in_normal);
    float facing = dot(n, view);
    if (facing < 0.0) {{  // light the side that is seen
        n = -n;
        facing = -facing;
    }}
    vec3 albedo = mix(in_color, vec3(0.95), surface.y) * surface.x;
    vec3 light = mix(GROUND, SKY, 0.5 + 0.5 * n.y) + KEY_COLOR * max(dot(n, KEY_DIRECTION), 0.0)
                 + HEADLIGHT * facing;
    float highlight = sharpen(max(dot(n, normalize(KEY_DIRECTION + view)), 0.0), shine.y)
                      + 0.5 * sharpen(facing, shine.y);
    float grazing = 1.0 - facing;
    float sky = clamp(reflect(-view, n).y * 0.8 + 0.35, 0.0, 1.0);
    vec3 mirror = SKY * (0.15 + 0.85 * sky) * (0.25 + 0.75 * grazing * grazing);
    vec3 tint = mix(vec3(1.0), in_color, surface.z);
    float falloff = 1.0 / (1.0 + 0.006 * distance * distance);
    vec3 lit = albedo * (light + surface.w * grazing * grazing) * falloff;
    vec3 shined = lit + tint * (shine.x * highlight + shine.z * mirror) * falloff;

    v_uv = in_uv;
    v_lit = srgb(lit);
    v_shine = srgb(shined) - v_lit;
    v_slant = u_pixel_angle / max(facing, 0.5);
    v_waves = u_materials[base];
    v_stripes = u_materials[base + 1];
    v_cells = u_materials[base + 2];
    v_grid = u_materials[base + 3];
    v_instance = in_instance;
    gl_Position = u_view_projection * vec4(in_position, 1.0);
}}
"""

FRAGMENT_SHADER = """
#version 330 core
uniform float u_max_depth;

in vec2 v_uv;
in vec3 v_lit;
in vec3 v_shine;
in float v_slant;
flat in vec4 v_waves;  // stripe and warp frequencies, cycles per metre
flat in vec4 v_stripes;  // warp, sharpness, amount, leaf tint
flat in vec4 v_cells;  // fine cells per metre, amount, coarse cells per metre, amount
flat in vec4 v_grid;  // cells per metre, cell warp, half line width in cells, amount
flat in int v_instance;

layout(location = 0) out vec4 out_color;
layout(location = 1) out float out_depth;
layout(location = 2) out int out_instance;

// Only arithmetic a CPU rasteriser vectorises well: no sin, pow, sqrt, derivatives or
// indexed loads. Every material runs the same code (a branch per material would be paid by
// every pixel); its parameters switch patterns on and off.

float hash(vec2 cell) {  // "hash without sine" (Hoskins), uniform in [0, 1)
    vec3 p = fract(cell.xyx * 0.1031);
    p += dot(p, p.yzx + 33.33);
    return fract((p.x + p.y) * p.z);
}

float bump(float cycles) {  // sine-like periodic bump: 0 at whole cycles, 1 half-way
    float f = fract(cycles);
    return 4.0 * f * (1.0 - f);
}

// 1 where a pattern has 4+ pixels per cycle, 0 from 2 down, where it would alias (moire).
float fade(float cycles_per_metre, float footprint) {
    return clamp(2.0 - 4.0 * cycles_per_metre * footprint, 0.0, 1.0);
}

void main() {
    vec2 uv = v_uv;
    float depth = 1.0 / gl_FragCoord.w;
    float footprint = depth * v_slant;  // metres of surface under this pixel
    float wave = bump(dot(uv, v_waves.xy) + v_stripes.x * bump(dot(uv, v_waves.zw)));
    float stripe = wave / (v_stripes.y - v_stripes.y * wave + wave);  // ~ pow(wave, sharpness)
    float fine = hash(floor(uv * v_cells.x)) - 0.5;
    vec2 coarse_cell = uv * v_cells.z;
    coarse_cell += v_grid.y * vec2(bump(coarse_cell.y * 0.43), bump(coarse_cell.x * 0.37));
    float coarse = hash(floor(coarse_cell)) - 0.5;
    vec2 in_cell = fract(uv * v_grid.x);
    float edge = min(min(in_cell.x, 1.0 - in_cell.x), min(in_cell.y, 1.0 - in_cell.y));
    float line = clamp(1.0 - (edge - v_grid.z) / (v_grid.x * footprint), 0.0, 1.0);

    float stripe_cycles = max(abs(v_waves.x), abs(v_waves.y));
    float shade = (1.0 - v_stripes.z * stripe * fade(stripe_cycles, footprint))
                  * (1.0 + v_cells.y * fine * max(fade(v_cells.x, footprint), 0.4))
                  * (1.0 + v_cells.w * coarse)
                  * (1.0 - v_grid.w * line * fade(v_grid.x, footprint));
    vec3 color = v_lit * shade;
    color.r += v_stripes.w * (coarse + 0.5) * color.g;

    out_color = vec4(color + v_shine, 1.0);
    out_depth = min(depth, u_max_depth);
    out_instance = v_instance;
}
"""
