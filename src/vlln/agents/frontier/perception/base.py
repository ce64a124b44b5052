"""The detector interface the frontier agent perceives through, and the privileged one.

A detector is simulated on the renderer's instance-id image: it says which of the instances
in view it detected (the others are blanked out of the image it hands back) and what it takes
each one for (:attr:`Detector.labels`: category and attributes). The agent sees objects only
through that, so swapping the detector changes its perception and nothing else.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from vlln.tasks.env import DetectedObject


class Detector(Protocol):
    """Object detection with attribute recognition, simulated on instance ids."""

    name: str

    @property
    def labels(self) -> Mapping[int, DetectedObject]:
        """What it reports each instance as whenever it detects it."""
        ...

    def detect(
        self, instance_ids: NDArray[np.int32], depth: NDArray[np.float32], pixel_area: int
    ) -> NDArray[np.int32]:
        """``instance_ids`` with every instance it misses in this frame set to 0.

        ``depth`` is the matching depth image (metres) and ``pixel_area`` the number of
        full-resolution pixels one pixel of these images stands for (they may be subsampled).
        """
        ...


class GroundTruthDetector:
    """A perfect detector: every instance in view, with its true category and attributes."""

    name = "truth"

    def __init__(self, truth: Mapping[int, DetectedObject]) -> None:
        self.labels = truth

    def detect(
        self, instance_ids: NDArray[np.int32], depth: NDArray[np.float32], pixel_area: int
    ) -> NDArray[np.int32]:
        return instance_ids
