"""The child side of :class:`vlln.gym.remote.RemoteEnv`: ``python -m vlln.gym.worker`` makes
one environment and answers pickled calls on standard input, replying on standard output."""

from __future__ import annotations

import os
import pickle
import sys
from typing import IO, Any

from vlln.gym.env import VllnEnv


def serve(commands: IO[bytes], replies: IO[bytes]) -> None:
    """Answer pickled ``(method, args, kwargs)`` calls until the input ends."""
    env: VllnEnv | None = None
    while True:
        try:
            method, args, kwargs = pickle.load(commands)
        except EOFError:
            break
        try:
            if method == "__init__":
                env, value = VllnEnv(*args, **kwargs), None
            else:
                value = getattr(env, method)(*args, **kwargs)
            reply: tuple[bool, Any] = (True, value)
        except Exception as error:  # raised again in the parent, where it belongs
            reply = (False, error)
        pickle.dump(reply, replies, pickle.HIGHEST_PROTOCOL)
        replies.flush()


if __name__ == "__main__":
    replies = os.fdopen(os.dup(sys.stdout.fileno()), "wb")
    os.dup2(sys.stderr.fileno(), sys.stdout.fileno())  # a stray print must not break the pipe
    serve(sys.stdin.buffer, replies)
