"""The VLFM-style baseline: frontier exploration ranked by a semantic value map.

VLFM (Yokoyama et al., "VLFM: Vision-Language Frontier Maps for Zero-Shot Semantic
Navigation", ICRA 2024) scores every frame by how likely the target is ahead, paints the
score onto the map cells in view (:mod:`.value_map`) and walks to the frontier of highest
value. Here a frame's score comes from what the agent's detector reports in it, through a
co-occurrence prior learned from the training houses (:mod:`.prior`): the categories in view
and the room type they suggest. Nothing else is read: no instance id is looked up beyond the
detector's own report, and the target's position is never used.

Everything else is the frontier agent's (mapping, planning, detection, the walk to a seen
instance of the target category, storeys), with asking off: VLFM does not talk.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from vlln.agents.frontier import FrontierAgent, FrontierConfig
from vlln.agents.frontier.mapping import Pose
from vlln.agents.frontier.storeys import Storey
from vlln.agents.vlfm.prior import CooccurrencePrior, shipped_prior
from vlln.agents.vlfm.value_map import ValueMap
from vlln.config import Positive, settings_dataclass
from vlln.tasks.env import EpisodeInfo, Observation


@settings_dataclass
class ValueRanking:
    """How a frontier's value trades off against the walk to it."""

    distance_scale: Positive = 5.0  # metres of extra walk worth one prior's worth of value
    radius: Positive = 0.6  # metres around a frontier whose values count


class ValueRanker:
    """Picks the reachable frontier with the best value (relative to the prior's) less the
    walk to it; an object, not a closure, so that agent snapshots copy it with the map."""

    def __init__(self, values: ValueMap, base: float, ranking: ValueRanking) -> None:
        self.values = values
        self.base = max(base, 1e-3)
        self.ranking = ranking

    def __call__(
        self, points: NDArray[np.float64], reach: NDArray[np.float64], pose: Pose
    ) -> int | None:
        reachable = np.flatnonzero(np.isfinite(reach))
        if reachable.size == 0:
            return None
        cfg = self.ranking
        scores = [
            self.values.around(float(points[i, 0]), float(points[i, 1]), cfg.radius) / self.base
            - float(reach[i]) / cfg.distance_scale
            for i in reachable
        ]
        return int(reachable[int(np.argmax(scores))])


class VlfmAgent(FrontierAgent):
    """Frontier agent whose frontier choice follows a value map (module doc)."""

    name = "vlfm"

    def __init__(
        self,
        seed: int = 0,
        config: FrontierConfig | None = None,
        detector: str = "truth",
        prior: CooccurrencePrior | None = None,
        ranking: ValueRanking | None = None,
    ) -> None:
        super().__init__(seed, replace(config or FrontierConfig(), asks=False), detector)
        self.name = "vlfm"
        self.prior = prior or shipped_prior()
        self.ranking = ranking or ValueRanking()
        self._values: list[ValueMap] = []  # per storey, in the order they were found
        self._default = 0.0

    def reset(self, episode: EpisodeInfo) -> None:
        self._values = []
        self._default = self.prior.frame_value(episode.object_category, {})
        super().reset(episode)

    @property
    def values(self) -> ValueMap:
        """The value map of the storey the agent is on."""
        return self._values[self.memory.current]

    def _new_storey(self, floor: float) -> Storey:
        storey = super()._new_storey(floor)
        values = ValueMap(storey.map, self._default)
        self._values.append(values)
        storey.explorer.rank = ValueRanker(values, self._default, self.ranking)
        return storey

    def _sense(self, observation: Observation, pose: Pose, tilt: float) -> None:
        super()._sense(observation, pose, tilt)
        if tilt != 0.0:
            return
        value = self.prior.frame_value(self.episode.object_category, self.seen_categories())
        self.values.add_frame(observation["depth"], pose, value)

    def seen_categories(self) -> dict[str, float]:
        """Pixels per category the detector reported in the last frame."""
        ids = self.tracker.last_detections
        found = ids[ids > 0]
        if found.size == 0:
            return {}
        labels = self.tracker.detector.labels
        pixels: Counter[str] = Counter()
        for instance_id, count in zip(*np.unique(found, return_counts=True), strict=True):
            label = labels.get(int(instance_id))
            if label is not None:
                pixels[label.category] += int(count) * self.tracker.pixel_area
        return dict(pixels)
