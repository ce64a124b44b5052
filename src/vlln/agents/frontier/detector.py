"""Candidates of the target category, from what the agent's detector reports.

The detector (:mod:`vlln.agents.frontier.perception`) hands back the instance-id image with
the instances it missed blanked out, and says what it takes each instance for (category and
attributes). Every detected instance reported as the target category that covers enough
pixels becomes a candidate; its pixels are back-projected with the depth into map cells, so
the agent knows where the object is (its footprint as seen so far) and can walk up to it.
Heights are measured from the start's floor; the lowest point seen of an object tells which
storey it stands on.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from vlln.agents.frontier.mapping import ObstacleMap, Pose
from vlln.agents.frontier.perception import Detector
from vlln.errors import ConfigError
from vlln.sim.camera import CameraSpec
from vlln.world.model import Attributes


@dataclass
class Candidate:
    """One instance of the target category that the agent has seen."""

    instance_id: int
    attributes: Attributes
    cells: NDArray[np.intp] = field(default_factory=lambda: np.zeros(0, np.intp))
    centres: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 2)))
    point_sum: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    point_count: int = 0
    best_pixels: int = 0  # most pixels (at full resolution) it covered in one frame
    lowest: float = math.inf  # height of its lowest point seen

    @property
    def centroid(self) -> tuple[float, float, float]:
        """Mean (x, y, z) of every back-projected pixel so far; y is height above the start."""
        mean = self.point_sum / max(self.point_count, 1)
        return float(mean[0]), float(mean[1]), float(mean[2])

    def distance_from(self, x: float, z: float) -> float:
        """Floor-plan distance from a point to the nearest cell the object was seen in."""
        if self.centres.shape[0] == 0:
            return math.inf
        return float(np.hypot(self.centres[:, 0] - x, self.centres[:, 1] - z).min())


@dataclass(frozen=True)
class Sighting:
    """How a candidate appears in the current frame (pixel counts at full resolution)."""

    pixels: int
    central_pixels: int  # inside rows H/4..3H/4 and columns W/4..3W/4
    column: float  # mean column of its pixels, 0 at the view's left edge, 1 at its right


class CandidateTracker:
    """Keeps the candidates of one category up to date, frame by frame."""

    def __init__(
        self,
        camera: CameraSpec,
        detector: Detector,
        category: str,
        obstacle_map: ObstacleMap,
        stride: int = 2,
        min_pixels: int = 100,
    ) -> None:
        if stride < 1:
            raise ConfigError(f"stride must be >= 1, got {stride}")
        self.camera = camera
        self.detector = detector
        self.map = obstacle_map
        self.min_pixels = min_pixels
        self._scale = stride * stride
        wanted = [i for i, d in detector.labels.items() if d.category == category and i > 0]
        self._lookup = np.zeros(max(wanted, default=0) + 2, bool)
        self._lookup[wanted] = True
        self._pixels = (slice(stride // 2, None, stride), slice(stride // 2, None, stride))
        us = np.arange(stride // 2, camera.width, stride)
        vs = np.arange(stride // 2, camera.height, stride)
        uu, vv = np.meshgrid(us, vs)
        self._rays = camera.pixel_ray(uu, vv)
        w, h = camera.width, camera.height
        self._columns = (uu + 0.5) / w
        self._central = (uu >= w / 4) & (uu < 3 * w / 4) & (vv >= h / 4) & (vv < 3 * h / 4)
        rows, cols = np.nonzero(self._central)
        self._central_window = (
            slice(int(rows.min()), int(rows.max()) + 1),
            slice(int(cols.min()), int(cols.max()) + 1),
        )
        self._last_ids = np.zeros(uu.shape, np.int32)
        self.candidates: dict[int, Candidate] = {}
        self.visible: dict[int, Sighting] = {}

    def update(
        self,
        instance_ids: NDArray[np.int32],
        depth: NDArray[np.float32],
        pose: Pose,
        tilt: float,
        height: float = 0.0,
    ) -> None:
        """Add one frame seen from ``pose`` with the feet ``height`` above the start's."""
        ids = self.detector.detect(
            np.asarray(instance_ids)[self._pixels], np.asarray(depth)[self._pixels], self._scale
        )
        self._last_ids = ids
        mask = np.take(self._lookup, ids, mode="clip")  # structure ids (< 0) read slot 0
        self.visible = {}
        if not mask.any():
            return
        d = np.asarray(depth)[self._pixels][mask].astype(np.float64)
        hit = (d > 0.0) & (d < self.camera.max_depth * 0.999)
        seen_ids = ids[mask]
        central = self._central[mask]
        columns = self._columns[mask]
        pose_matrix = self.camera.camera_to_world((pose.x, height, pose.z), pose.yaw, tilt)
        points = (self._rays[mask] * d[:, None]) @ pose_matrix[:3, :3].T + pose_matrix[:3, 3]
        for instance_id in np.unique(seen_ids).tolist():
            mine = seen_ids == instance_id
            pixels = int(np.count_nonzero(mine)) * self._scale
            self.visible[instance_id] = Sighting(
                pixels,
                int(np.count_nonzero(mine & central)) * self._scale,
                float(columns[mine].mean()),
            )
            usable = mine & hit
            if not usable.any():
                continue
            candidate = self.candidates.get(instance_id)
            if candidate is None:
                candidate = Candidate(instance_id, self.detector.labels[instance_id].attributes)
                self.candidates[instance_id] = candidate
            own = points[usable]
            candidate.point_sum += own.sum(axis=0)
            candidate.point_count += own.shape[0]
            candidate.best_pixels = max(candidate.best_pixels, pixels)
            candidate.lowest = min(candidate.lowest, float(own[:, 1].min()))
            cells = np.union1d(candidate.cells, self.map.flat_cells(own[:, 0], own[:, 2]))
            if cells.size != candidate.cells.size:
                candidate.cells = cells
                n_cols = self.map.shape[1]
                s, (ox, oz) = self.map.cell_size, self.map.origin
                candidate.centres = np.stack(
                    [ox + (cells % n_cols + 0.5) * s, oz + (cells // n_cols + 0.5) * s], axis=1
                )

    def centred(self, instance_id: int, min_pixels: int) -> bool:
        """Whether the current view is unmistakably of this instance: at least ``min_pixels``
        of it in the image centre, more than any other instance of the category there, and
        either the object with most pixels in the centre or at least half of it inside the
        centre. Asking "is this the one?" about anything less invites a misleading "no"."""
        sighting = self.visible.get(instance_id)
        if sighting is None or sighting.central_pixels < min_pixels:
            return False
        rivals = (s.central_pixels for i, s in self.visible.items() if i != instance_id)
        if any(pixels >= sighting.central_pixels for pixels in rivals):
            return False
        if 2 * sighting.central_pixels >= sighting.pixels:
            return True
        centre = self._last_ids[self._central_window]
        ids, counts = np.unique(centre[centre > 0], return_counts=True)
        return ids.size > 0 and int(ids[np.argmax(counts)]) == instance_id

    def in_view(self, min_pixels: int, ruled_out: set[int]) -> list[tuple[int, float]]:
        """Candidates seen well enough to act on, not ``ruled_out``, that the current frame
        shows with at least ``min_pixels``, as (id, mean column), left to right."""
        seen = [
            (instance, sighting.column)
            for instance, sighting in self.visible.items()
            if sighting.pixels >= min_pixels
            and instance not in ruled_out
            and self.candidates.get(instance) is not None
            and self.candidates[instance].best_pixels >= self.min_pixels
        ]
        return sorted(seen, key=lambda item: item[1])

    @property
    def last_detections(self) -> NDArray[np.int32]:
        """The last frame's instance ids as the detector reported them (missed ones 0), at
        every ``stride``-th pixel: what it saw, of every category."""
        return self._last_ids

    @property
    def pixel_area(self) -> int:
        """Full-resolution pixels one pixel of :attr:`last_detections` stands for."""
        return self._scale

    def detected(self) -> list[Candidate]:
        """Candidates seen well enough to act on, by id."""
        return [c for _, c in sorted(self.candidates.items()) if c.best_pixels >= self.min_pixels]
