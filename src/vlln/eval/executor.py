"""Where a runner's work is played: the one protocol of the executors of ``vlln eval``
(:class:`vlln.eval.runner.LocalExecutor`, :class:`vlln.cluster.evaluation.RayExecutor`) and of
``vlln data build`` (:class:`vlln.datagen.build.LocalBuilder`,
:class:`vlln.cluster.data.RayBuilder`).

A runner owns its folder: the settings it was started with, what is left to do, resume,
writing and progress. An executor only plays a list of work items somewhere (this process, a
Ray cluster) and hands the results back through ``commit`` in the items' order, so the folder
is the same whoever played it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol, TypeVar

Job = TypeVar("Job", contravariant=True)
Work = TypeVar("Work")
Result = TypeVar("Result")


class Executor(Protocol[Job, Work, Result]):
    """Plays a runner's ``items`` of one ``job`` somewhere and hands every result back, in
    order."""

    @property
    def label(self) -> str:
        """How the progress bar names where it plays ("" for this process)."""

    def check(self, job: Job) -> None:
        """Fail in one line before any work (the agent cannot be made, no cluster)."""

    def play(self, job: Job, items: list[Work], commit: Callable[[list[Result]], None]) -> None:
        """Play ``items`` and call ``commit`` with their results in order, each once, as soon
        as they and every earlier one are in."""
