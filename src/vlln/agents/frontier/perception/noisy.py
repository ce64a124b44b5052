"""A detector with the errors of a real one: misses, look-alike categories, misread attributes.

The model (documented with its constants in docs/perception.md):

* **Recall** per frame and visible instance, from its apparent size ``a`` (pixels at 640x480)
  and distance ``d`` (mean depth of its pixels, metres)::

      p(d, a) = max_recall * a / (a + half_area) * 1 / (1 + (d / half_distance) ** power)

  Each frame draws afresh, so an object missed from afar is usually found on the way to it.
* **Category confusions**, per instance and for the whole episode (a detector takes the same
  stool for a chair from every side): with ``confusion_rate`` an instance whose category has
  look-alikes (:mod:`.confusions`) is reported as one of them, each equally likely.
* **Attribute errors**, per instance and for the whole episode: the colour is misread as one
  of its nearest named colours with ``color_error_rate``, the material as a look-alike with
  ``material_error_rate`` (the texture word follows the material read), the relative size by
  one step with ``size_error_rate``.

Every draw comes from generators seeded by the agent's seed and the episode, so the same seed
gives the same detections.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from vlln.agents.frontier.perception.confusions import (
    COLOR_LOOKALIKES,
    MATERIAL_LOOKALIKES,
    SIZE_LOOKALIKES,
    category_lookalikes,
)
from vlln.config import Positive, Probability, settings_dataclass
from vlln.tasks.env import DetectedObject
from vlln.world.materials import MATERIAL_TEXTURE

_LABEL_STREAM = 0  # seeds the per-instance (whole-episode) errors
_FRAME_STREAM = 1  # seeds the per-frame misses


@settings_dataclass
class NoiseModel:
    """Constants of the noise model (module doc); rates are probabilities."""

    max_recall: Probability = 0.95  # a large, near object is still missed 5 % of frames
    half_area: Positive = 400.0  # pixels at 640x480 where the size factor is 1/2
    half_distance: Positive = 4.0  # metres where the distance factor is 1/2
    power: Positive = 4.0  # how sharply recall falls past half_distance
    confusion_rate: Probability = 0.2
    color_error_rate: Probability = 0.2
    material_error_rate: Probability = 0.15
    size_error_rate: Probability = 0.1

    def recall(
        self, distance: NDArray[np.float64], area: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        """Probability of detecting an instance at ``distance`` metres covering ``area``
        pixels in one frame."""
        size_factor = area / (area + self.half_area)
        distance_factor = 1.0 / (1.0 + (distance / self.half_distance) ** self.power)
        return self.max_recall * size_factor * distance_factor


class NoisyDetector:
    """Detections through :class:`NoiseModel`; ``truth`` is the raw source it corrupts."""

    name = "noisy"

    def __init__(
        self,
        truth: Mapping[int, DetectedObject],
        seed: Sequence[int],
        model: NoiseModel | None = None,
    ) -> None:
        self.model = model or NoiseModel()
        self.labels = misread_labels(
            truth, self.model, np.random.default_rng([*seed, _LABEL_STREAM])
        )
        self._frames = np.random.default_rng([*seed, _FRAME_STREAM])

    def detect(
        self, instance_ids: NDArray[np.int32], depth: NDArray[np.float32], pixel_area: int
    ) -> NDArray[np.int32]:
        ids = np.asarray(instance_ids)
        slots = np.maximum(ids, 0).ravel()  # structure (< 0) and background share slot 0
        counts = np.bincount(slots)
        visible = np.nonzero(counts[1:])[0] + 1
        if visible.size == 0:
            return ids
        # an object's pixels always have a depth (0 only where nothing was drawn)
        depth_sum = np.bincount(slots, weights=np.asarray(depth).ravel(), minlength=counts.size)
        distance = depth_sum[visible] / counts[visible]
        area = counts[visible].astype(np.float64) * pixel_area
        found = self._frames.random(visible.size) < self.model.recall(distance, area)
        if found.all():
            return ids
        keep = np.ones(counts.size, bool)
        keep[visible[~found]] = False
        return np.where(keep[slots].reshape(ids.shape), ids, 0).astype(ids.dtype, copy=False)


def misread_labels(
    truth: Mapping[int, DetectedObject], model: NoiseModel, rng: np.random.Generator
) -> dict[int, DetectedObject]:
    """What the detector takes each instance for, for a whole episode. Every instance uses
    the same number of draws, in id order, so one instance's errors never shift another's."""
    labels = {}
    for instance_id in sorted(truth):
        true = truth[instance_id]
        chance = rng.random(4)
        pick = rng.integers(0, 1 << 30, 4)
        category = _misread(
            true.category,
            category_lookalikes(true.category),
            model.confusion_rate,
            chance[0],
            pick[0],
        )
        attributes = true.attributes
        color = _misread(
            attributes.color,
            COLOR_LOOKALIKES.get(attributes.color, ()),
            model.color_error_rate,
            chance[1],
            pick[1],
        )
        material = _misread(
            attributes.material,
            MATERIAL_LOOKALIKES.get(attributes.material, ()),
            model.material_error_rate,
            chance[2],
            pick[2],
        )
        texture = attributes.texture
        if material != attributes.material:
            texture = MATERIAL_TEXTURE.get(material, texture)
        size = _misread(
            attributes.size,
            SIZE_LOOKALIKES.get(attributes.size, ()),
            model.size_error_rate,
            chance[3],
            pick[3],
        )
        read = replace(attributes, color=color, material=material, texture=texture, size=size)
        labels[instance_id] = DetectedObject(category, read)
    return labels


def _misread(value: str, lookalikes: tuple[str, ...], rate: float, chance: float, pick: int) -> str:
    if not lookalikes or chance >= rate:
        return value
    return lookalikes[int(pick) % len(lookalikes)]
