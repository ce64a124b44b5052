"""Which past frames a sample shows as its historical observations (reference-facts §6)."""

from __future__ import annotations

from collections.abc import Iterable


def uniform_frames(frame: int, count: int) -> list[int]:
    """``count`` of the past frames ``0 .. frame-1`` spread evenly and ending with the latest
    one (all of them when there are no more than ``count``).

    Sample ``i`` is frame ``(i + 1) * frame // count - 1``: integer arithmetic, so the choice
    is exact and identical on every machine.
    """
    if frame <= count:
        return list(range(frame))
    return [(i + 1) * frame // count - 1 for i in range(count)]


def history_frames(frame: int, dialog_frames: Iterable[int], count: int) -> list[int]:
    """The uniform sample plus every earlier frame at which a question was asked, in order."""
    earlier_dialog = {f for f in dialog_frames if f < frame}
    return sorted(set(uniform_frames(frame, count)) | earlier_dialog)
