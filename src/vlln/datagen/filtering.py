"""Which collected trajectories are good enough to train on (docs/reference-facts.md §5, filtering).

Dropped, with the first reason that applies: the collector gave up (target never found, step
limit), any collision, more than ``max_consecutive_turns`` turns in a row, or final frames
(level and 30° down) neither of which shows the target (on ObjectNav: the instance walked to)
inside the central 3/4 x 3/4 of the image.

The opening 360° scan is 12 turns by design; counted together with the turns that then face
the first frontier it would exceed 13 in nearly every trajectory, so the turn-run rule applies
to the actions after the scan (``scan_turns``).
"""

from __future__ import annotations

from pydantic import Field

from vlln.config import Count, settings_dataclass
from vlln.datagen.collector.collect import TOO_LONG
from vlln.datagen.collector.policy import NOT_FOUND
from vlln.datagen.collector.visibility import best_central_pixels
from vlln.datagen.trajectory import Trajectory
from vlln.sim.agent import Action
from vlln.sim.renderer import Frame

COLLISION = "collision"
TOO_MANY_TURNS = "too_many_consecutive_turns"
TARGET_NOT_CENTRED = "target_not_in_final_view"
REASONS = (NOT_FOUND, TOO_LONG, COLLISION, TOO_MANY_TURNS, TARGET_NOT_CENTRED)


@settings_dataclass
class FilterConfig:
    max_consecutive_turns: Count = 13
    scan_turns: int = Field(default=12, ge=0)  # the opening scan, not counted in turn runs
    min_target_pixels: Count = 100  # target pixels inside the central region of the last frame


def longest_turn_run(actions: list[Action]) -> int:
    """The most TURN_LEFT/TURN_RIGHT actions in a row."""
    longest = run = 0
    for action in actions:
        run = run + 1 if action in (Action.TURN_LEFT, Action.TURN_RIGHT) else 0
        longest = max(longest, run)
    return longest


def rejection_reason(
    trajectory: Trajectory, final_frames: tuple[Frame, ...], config: FilterConfig | None = None
) -> str | None:
    """Why the trajectory is dropped, or None to keep it."""
    config = config or FilterConfig()
    if trajectory.failure is not None:
        return trajectory.failure
    if any(step.collided for step in trajectory.steps):
        return COLLISION
    after_scan = [s.action for s in trajectory.steps[config.scan_turns :]]
    if longest_turn_run(after_scan) > config.max_consecutive_turns:
        return TOO_MANY_TURNS
    target_id = int(trajectory.target_key)
    final_ids = tuple(frame.instance_ids for frame in final_frames)
    if best_central_pixels(final_ids, target_id) < config.min_target_pixels:
        return TARGET_NOT_CENTRED
    return None
