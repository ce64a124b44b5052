"""Headless OpenGL contexts through EGL.

EGL needs no display server, so the same code renders on a GPU (vendor EGL driver) and on a
machine without one (Mesa's llvmpipe rasterises on the CPU cores). What is missing on a bare
machine is a system library, not a Python package, so the error says which packages to install.

A process forked after it made a context cannot render: Mesa's worker threads do not survive
the fork, and the child's first draw waits for them for ever, even in a context it makes anew.
Such a child is told so (:func:`forked_after_gl`, and one line from
:func:`create_headless_context`) instead of hanging; a process started by spawning renders.
"""

from __future__ import annotations

import os
from typing import Any

import moderngl

from vlln.errors import RendererUnavailableError

REQUIRED_GL_VERSION = 330
INSTALL_HINT = (
    "install the system packages libegl1 and libgl1-mesa-dri "
    "(Debian/Ubuntu: apt-get install libegl1 libgl1-mesa-dri); on a GPU machine the vendor "
    "driver's EGL library is used instead"
)


FORKED_HINT = (
    "this process was forked from one that had already rendered, and Mesa's OpenGL cannot "
    "render after such a fork; start worker processes by spawning them instead (e.g. "
    "multiprocessing.get_context('spawn'))"
)
_GL = {"made": False, "inherited": False}  # made a context here; forked from one that had


def _after_fork_in_child() -> None:
    _GL["inherited"] = _GL["inherited"] or _GL["made"]


os.register_at_fork(after_in_child=_after_fork_in_child)


def forked_after_gl() -> bool:
    """Whether this process was forked (at any remove) from one that had made a context."""
    return _GL["inherited"]


def create_headless_context() -> moderngl.Context:
    """A standalone OpenGL 3.3+ core context on the default EGL device."""
    if _GL["inherited"]:
        raise RendererUnavailableError(FORKED_HINT)
    options: dict[str, Any] = {"standalone": True, "backend": "egl"}
    try:
        context = moderngl.create_context(require=REQUIRED_GL_VERSION, **options)
    except Exception as error:  # glcontext raises plain Exceptions for every failure
        raise RendererUnavailableError(
            f"could not create a headless OpenGL {REQUIRED_GL_VERSION // 100}."
            f"{REQUIRED_GL_VERSION % 100 // 10} context through EGL ({error}); {INSTALL_HINT}"
        ) from error
    _GL["made"] = True
    return context


def renderer_description(context: moderngl.Context) -> str:
    """Vendor, renderer and version strings, e.g. to tell llvmpipe from a GPU in a report."""
    info = context.info
    return f"{info['GL_VENDOR']} | {info['GL_RENDERER']} | {info['GL_VERSION']}"
