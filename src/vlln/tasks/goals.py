"""An episode's goals in its scene: the target instances the episode names, and the view
points from which each counts as reached."""

from __future__ import annotations

from collections.abc import Sequence

from vlln.errors import ConfigError, EpisodeRefusedError
from vlln.sim.simulator import Simulator
from vlln.sim.viewpoints import GoalPoint
from vlln.tasks.episode import Episode
from vlln.tasks.refusal import no_goal_reason, on_the_storey
from vlln.tasks.spec import TaskType
from vlln.world.model import Box3, House, ObjectInstance


def goal_points(
    sim: Simulator, episode: Episode, targets: Sequence[ObjectInstance]
) -> list[GoalPoint]:
    """The goals' view points; a goal listing none gets those of its box (reference §1).
    ``(x, z)`` on one storey (listed points off its floor are not its), ``(x, y, z)`` in a
    house with several; none at all refuses the episode (:mod:`vlln.tasks.refusal`)."""
    points: list[GoalPoint] = []
    storeys = sim.storeys
    listed = 0
    for k, goal in enumerate(episode.goals):
        if goal.view_points and storeys is not None:
            points += [vp.position for vp in goal.view_points]
            continue
        if goal.view_points:
            listed += len(goal.view_points)
            points += [
                (vp.position[0], vp.position[2])
                for vp in goal.view_points
                if on_the_storey(sim, vp.position[1])
            ]
            continue
        if goal.bbox is not None:
            x0, y0, z0, x1, y1, z1 = goal.bbox
            box = Box3((x0, y0, z0), (x1, y1, z1))
        elif k < len(targets):
            box = targets[k].box
        else:
            box = Box3(goal.position, goal.position)
        points += sim.view_points(box)
    if not points:
        reason = no_goal_reason(sim, listed)
        raise EpisodeRefusedError(episode.episode_id, episode.scene_id, reason)
    return points


def goal_instances(house: House, episode: Episode, task: TaskType) -> list[ObjectInstance]:
    """The instances that are goals: every one of the category for ObjectNav, else those the
    instruction names."""
    if task == TaskType.OBJECTNAV:
        found = house.instances_of(episode.object_category)
    else:
        try:
            found = [house.instance_for_key(i) for i in episode.instruction.instance_id]
        except KeyError as error:
            raise ConfigError(
                f"episode {episode.episode_id}: {error.args[0]}; the episode file and the "
                "scene do not match"
            ) from None
    if not found:
        raise ConfigError(
            f"episode {episode.episode_id} names no goal instance of "
            f"{episode.object_category!r} in {episode.scene_id}"
        )
    return found
