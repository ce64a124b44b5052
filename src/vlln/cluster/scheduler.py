"""Connecting to a cluster, and collecting task results in order as they finish.

Retries are explicit: a chunk whose worker process or node dies is re-run up to
``max_retries`` times (``max_retries`` on the task). Exceptions raised by our own code are not
retried, since a rerun would raise them again, except the few a task names (a failure beside
it, such as a lost model server). Results are handed to the driver's ``commit``
in submission order, each exactly once, as soon as every earlier one is in; when a chunk
fails for good, the results already in are committed (out of order) before the error, so no
finished work is lost and a rerun resumes.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from vlln.errors import ConfigError, VllnError
from vlln.extras import install_command

DEFAULT_MAX_RETRIES = 3


class ClusterError(VllnError):
    """A chunk of work failed on the cluster after its retries."""


def import_ray() -> Any:
    try:
        import ray
    except ImportError:
        raise ConfigError(f"running on Ray needs the ray extra: {install_command('ray')}") from None
    return ray


def connect(address: str | None) -> Any:
    """Ray, initialised: the cluster at ``address`` ("auto": the one on this machine), or
    ``RAY_ADDRESS``'s, or a fresh local one when neither is given."""
    ray = import_ray()
    if not ray.is_initialized():
        try:
            ray.init(address=address or None, log_to_driver=False)
        except ConnectionError as error:
            raise ConfigError(
                f"cannot reach a Ray cluster at {address!r} ({error}); start one with "
                "`ray start --head` or pass --ray without an address for a local one"
            ) from None
    return ray


def remote_function(
    function: Callable[..., Any],
    max_retries: int,
    retry_on: tuple[type[Exception], ...] = (),
) -> Any:
    """``function`` as a Ray task with explicit retries for a dead worker, and for the
    exceptions in ``retry_on`` (failures of something beside the task, such as its model
    server, that a rerun can get past)."""
    if max_retries < 0:
        raise ConfigError(f"max_retries must be >= 0, got {max_retries}")
    ray = import_ray()
    retry_exceptions = list(retry_on) if retry_on else False
    return ray.remote(function).options(max_retries=max_retries, retry_exceptions=retry_exceptions)


def collect_in_order(refs: Sequence[Any], commit: Callable[[int, Any], None]) -> None:
    """Call ``commit(i, result)`` for every task ``refs[i]`` in order (module doc)."""
    ray = import_ray()
    pending = {ref: index for index, ref in enumerate(refs)}
    ready: dict[int, Any] = {}
    next_index = 0
    while pending:
        done, _ = ray.wait(list(pending), num_returns=1)
        for ref in done:
            index = pending.pop(ref)
            try:
                ready[index] = ray.get(ref)
            except Exception as error:
                for earlier in sorted(ready):
                    commit(earlier, ready[earlier])
                for ref_left in pending:
                    ray.cancel(ref_left)
                raise ClusterError(
                    f"chunk {index} failed on the cluster after its retries: {_reason(error)}; "
                    "finished results are saved, rerun the same command to resume"
                ) from None
        while next_index in ready:
            commit(next_index, ready.pop(next_index))
            next_index += 1


def _reason(error: Exception) -> str:
    """One line on why a task failed: the exception raised in it (not Ray's wrapper with the
    remote traceback), or what happened to its worker."""
    cause = getattr(error, "cause", None)
    reason = cause if isinstance(cause, Exception) else error
    lines = str(reason).strip().splitlines()
    return f"{type(reason).__name__}: {lines[0][:500] if lines else ''}"
