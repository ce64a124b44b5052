"""Headless OpenGL contexts through EGL.

EGL needs no display server, so the same code renders on a GPU (vendor EGL driver) and on a
machine without one (Mesa's llvmpipe rasterises on the CPU cores). What is missing on a bare
machine is a system library, not a Python package, so the error says which packages to install.
"""

from __future__ import annotations

from typing import Any

import moderngl

from vlln.errors import RendererUnavailableError

REQUIRED_GL_VERSION = 330
INSTALL_HINT = (
    "install the system packages libegl1 and libgl1-mesa-dri "
    "(Debian/Ubuntu: apt-get install libegl1 libgl1-mesa-dri); on a GPU machine the vendor "
    "driver's EGL library is used instead"
)


def create_headless_context() -> moderngl.Context:
    """A standalone OpenGL 3.3+ core context on the default EGL device."""
    options: dict[str, Any] = {"standalone": True, "backend": "egl"}
    try:
        context = moderngl.create_context(require=REQUIRED_GL_VERSION, **options)
    except Exception as error:  # glcontext raises plain Exceptions for every failure
        raise RendererUnavailableError(
            f"could not create a headless OpenGL {REQUIRED_GL_VERSION // 100}."
            f"{REQUIRED_GL_VERSION % 100 // 10} context through EGL ({error}); {INSTALL_HINT}"
        ) from error
    return context


def renderer_description(context: moderngl.Context) -> str:
    """Vendor, renderer and version strings, e.g. to tell llvmpipe from a GPU in a report."""
    info = context.info
    return f"{info['GL_VENDOR']} | {info['GL_RENDERER']} | {info['GL_VERSION']}"
