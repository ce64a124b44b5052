"""The instance-id image alone, drawn by a program that computes nothing else.

The oracle (and the service that hosts it) looks only at which object covers which pixel.
The full program lights every vertex and textures every pixel for the colour image; on a
CPU rasteriser that shading is most of a frame's cost. This pass draws the same triangles,
in the same order, from the same vertex and index buffers with the same depth test and face
culling, into the renderer's own id and depth attachments, so its image equals the full
pass's id output pixel for pixel. Both vertex shaders declare ``gl_Position`` invariant,
which is what the GLSL specification asks for positions to agree between two programs.

moderngl holds Python's global interpreter lock through every call, including the read-back
that waits for the rasteriser; a server that renders on one thread would then stall all its
other threads for the whole frame. So the pass waits for the frame with ``glFinish`` called
through ctypes, which releases the lock, and reads back only once the pixels are done.
"""

from __future__ import annotations

import ctypes
import functools
from collections.abc import Callable

import moderngl
import numpy as np
from numpy.typing import NDArray

from vlln.sim.shaders import VERTEX_DTYPE, program_uniform

ID_VERTEX_SHADER = """
#version 330 core
uniform mat4 u_view_projection;

in vec3 in_position;
in int in_instance;

flat out int v_instance;
invariant gl_Position;

void main() {
    v_instance = in_instance;
    gl_Position = u_view_projection * vec4(in_position, 1.0);
}
"""

ID_FRAGMENT_SHADER = """
#version 330 core
flat in int v_instance;

layout(location = 0) out int out_instance;

void main() {
    out_instance = v_instance;
}
"""


@functools.cache
def gl_finish() -> Callable[[], None] | None:
    """``glFinish`` of the system's OpenGL dispatch library (it acts on the context current on
    the calling thread), or None where there is none: then the read-back waits instead,
    holding the lock."""
    for name in ("libOpenGL.so.0", "libGL.so.1"):
        try:
            finish: Callable[[], None] = ctypes.CDLL(name).glFinish
        except (OSError, AttributeError):
            continue
        return finish
    return None


def id_vertex_format() -> str:
    """The moderngl format that reads only the position and the instance id of each vertex
    record and skips the other fields (derived from :data:`VERTEX_DTYPE`, so it follows that
    layout if it changes)."""
    kept = {"position": "3f", "instance": "1i"}
    names = VERTEX_DTYPE.names or ()
    return " ".join(kept.get(name, f"{VERTEX_DTYPE[name].itemsize}x") for name in names)


class InstanceIdPass:
    """Draws instance ids into ``id_attachment`` (R32I) with ``depth_attachment``; everything
    it is given belongs to the caller, who keeps the GL context current around each call."""

    def __init__(
        self,
        ctx: moderngl.Context,
        vertex_buffer: moderngl.Buffer,
        index_buffer: moderngl.Buffer,
        id_attachment: moderngl.Renderbuffer,
        depth_attachment: moderngl.Renderbuffer,
    ) -> None:
        self._program = ctx.program(
            vertex_shader=ID_VERTEX_SHADER, fragment_shader=ID_FRAGMENT_SHADER
        )
        self._vertex_array = ctx.vertex_array(
            self._program,
            [(vertex_buffer, id_vertex_format(), "in_position", "in_instance")],
            index_buffer=index_buffer,
            index_element_size=4,
        )
        self._framebuffer = ctx.framebuffer([id_attachment], depth_attachment)

    def draw(self, view_projection: bytes, vertices: int, out: NDArray[np.int32]) -> None:
        """Draw the first ``vertices`` entries of the index buffer (already written by the
        caller) with this view-projection matrix and read the ids into ``out``."""
        program_uniform(self._program, "u_view_projection").write(view_projection)
        self._framebuffer.use()
        self._framebuffer.clear(0.0, 0.0, 0.0, 0.0, depth=1.0)
        if vertices > 0:
            self._vertex_array.render(moderngl.TRIANGLES, vertices=vertices)
            finish = gl_finish()
            if finish is not None:
                finish()  # other Python threads run while the rasteriser works
        self._framebuffer.read_into(out, components=1, attachment=0, dtype="i4")

    def release(self) -> None:
        """Free this pass's GL objects (not the buffers and attachments it was given)."""
        self._framebuffer.release()
        self._vertex_array.release()
        self._program.release()
