"""Which frames of a trajectory show a same-category distractor: where ``--hard-negatives``
writes its samples.

A model that matches the target's category but weakly its attributes stops at the first
instance of the category it sees (the paper's AD failure). The teacher walked on past such
instances; a sample at each frame where one is in plain view, with the teacher's move there,
teaches walking on (or asking). "In plain view" is the collector's own rule for the target at
its STOP (:func:`~vlln.datagen.collector.visibility.central_pixels` of the level view, at
least :data:`DISTRACTOR_PIXELS`), and the distractor must show more than the target: where
the target shows as much, the view is one of the target as well. Only IIGN and IGN have
distractors: in ObjectNav every instance of the category is a goal.

The view is rendered again, instance ids only, from the frame's stored level pose, in the
house the scene id names, built as the data build builds it (:class:`SceneCache`).
"""

from __future__ import annotations

from collections.abc import Callable

from vlln.datagen.collector.policy import PolicyConfig
from vlln.datagen.collector.visibility import central_pixels
from vlln.datagen.layout import level_state
from vlln.datagen.reader import HouseDataset
from vlln.datagen.sft.source import SourceTrajectory
from vlln.errors import ConfigError
from vlln.tasks.scenes import SceneCache, is_procedural

DISTRACTOR_TASKS = ("iign", "ign")
DISTRACTOR_PIXELS = PolicyConfig().final_pixels
"""Central pixels that put a distractor in plain view: as many as the collector wants of the
target to stop, so the view would have met the teacher's stop rule had it been the target."""


class DistractorViews:
    """Renders the level views of trajectories again to find same-category distractors."""

    def __init__(self) -> None:
        self._scenes = SceneCache(capacity=1)  # an export reads its houses one after another

    def shows_distractor(
        self, house: HouseDataset, trajectory: SourceTrajectory
    ) -> Callable[[int], bool]:
        """The test of a frame of ``trajectory`` (stored in ``house``): whether its level view
        shows a non-target instance of the target's category in plain view, more than the
        target. It renders only when asked, so frames without a move to train cost nothing."""
        if not trajectory.target or not is_procedural(trajectory.scene_id):
            raise ConfigError(
                f"episode {trajectory.episode_key} of {house.root} names no target instance or "
                f"no procedural house ({trajectory.scene_id!r}); --hard-negatives renders the "
                "house again, so it takes datasets built by `vlln data build` only"
            )
        sim = self._scenes.get(trajectory.scene_id)
        target = sim.house.instance_for_key(trajectory.target)
        others = [i.id for i in sim.house.instances_of(target.category) if i.id != target.id]
        poses = house.frames(trajectory.episode_index)[f"pose.{house.settings['level']}"]

        def shows(frame: int) -> bool:
            if not others:
                return False
            ids = sim.render_instance_ids(level_state(sim.config.camera, poses[frame]))
            least = max(DISTRACTOR_PIXELS, central_pixels(ids, target.id) + 1)
            return any(central_pixels(ids, other) >= least for other in others)

        return shows

    def close(self) -> None:
        self._scenes.close()
