"""A process forked after OpenGL was used is told it cannot render, instead of hanging."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import vlln

_FORK = """
import os
from vlln.errors import RendererUnavailableError
from vlln.sim.gl_context import create_headless_context, forked_after_gl
context = create_headless_context()
framebuffer = context.simple_framebuffer((8, 8))
framebuffer.use()
framebuffer.clear(1.0, 0.0, 0.0, 1.0)
framebuffer.read()
pid = os.fork()
if pid == 0:
    try:
        create_headless_context()
        os._exit(3)
    except RendererUnavailableError as error:
        os._exit(0 if forked_after_gl() and "spawn" in str(error) else 4)
_, status = os.waitpid(pid, 0)
print(os.waitstatus_to_exitcode(status), forked_after_gl())
"""


def test_a_child_forked_after_rendering_refuses_to_make_a_context() -> None:
    root = str(Path(vlln.__file__).resolve().parents[1])
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([root, os.environ.get("PYTHONPATH", "")])}
    process = subprocess.Popen(
        [sys.executable, "-c", _FORK],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        out, err = process.communicate(timeout=120)
    except subprocess.TimeoutExpired:  # the child hung drawing: kill it and its parent
        os.killpg(process.pid, signal.SIGKILL)
        process.communicate()
        raise AssertionError("the forked child hung instead of refusing") from None
    assert process.returncode == 0, err
    assert out.split() == ["0", "False"]  # the child refused; the parent itself is fine
