"""An environment run in a fresh Python process, for a process that cannot render itself.

Gymnasium's ``AsyncVectorEnv`` forks its workers by default (on Linux before Python 3.14).
A worker forked from a process that had already rendered cannot render
(:func:`vlln.sim.gl_context.forked_after_gl`), so there :class:`vlln.gym.env.VllnEnv` plays
its episodes in a new interpreter started with ``python -m vlln.gym.worker`` and relays each
call over its standard input and output, pickled. A new interpreter shares nothing with the
forked one, so it makes its OpenGL context anew; nothing re-runs the user's script either.
"""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
from pathlib import Path
from typing import Any

from vlln.errors import ConfigError, RendererUnavailableError

_PACKAGE_ROOT = str(Path(__file__).resolve().parents[2])  # the folder holding vlln/


class RemoteEnv:
    """A ``VllnEnv(**arguments)`` in a child interpreter; :meth:`call` runs its methods."""

    def __init__(self, arguments: dict[str, Any]) -> None:
        path = os.pathsep.join(filter(None, [_PACKAGE_ROOT, os.environ.get("PYTHONPATH")]))
        self._process = subprocess.Popen(
            [sys.executable, "-m", "vlln.gym.worker"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            env={**os.environ, "PYTHONPATH": path},
        )
        try:
            self.call("__init__", **arguments)
        except BaseException:
            self._end()
            raise

    def call(self, method: str, *args: Any, **kwargs: Any) -> Any:
        """``env.method(*args, **kwargs)`` in the child; its exception is raised here."""
        stdin, stdout = self._process.stdin, self._process.stdout
        assert stdin is not None and stdout is not None
        try:
            message = pickle.dumps((method, args, kwargs), pickle.HIGHEST_PROTOCOL)
        except (pickle.PicklingError, TypeError, AttributeError) as error:
            raise ConfigError(
                f"{method}'s arguments cannot be sent to the environment's own process ({error}); "
                "pass arguments that pickle, e.g. oracle='rule'"
            ) from None
        try:
            stdin.write(message)
            stdin.flush()
            ok, value = pickle.load(stdout)
        except (EOFError, OSError):
            raise RendererUnavailableError(
                "the environment's process (python -m vlln.gym.worker) ended; its error is "
                "printed above"
            ) from None
        if not ok:
            raise value
        return value

    def close(self) -> None:
        if self._process.poll() is None:
            self.call("close")
        self._end()

    def _end(self) -> None:
        for pipe in (self._process.stdin, self._process.stdout):
            if pipe is not None:
                pipe.close()  # the child ends at the end of its input
        self._process.wait()
