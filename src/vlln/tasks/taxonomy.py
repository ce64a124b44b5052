"""The failure taxonomy of VL-LN Bench: every episode is a success or exactly one failure.

The paper (supplementary, "Failure analysis") defines five failure modes in words:

* **missed detection** (MD): the agent observes the target but fails to recognise it, and
  explores until the step budget is spent;
* **wrong detection** (WD): it stops at an object of the wrong category;
* **ambiguous detection** (AD): it stops at a same-category distractor rather than the target;
* **exploration failure** (Expl): it never observes the target;
* **stop failure** (ST): it stops near the target (within 1 m) but outside the success
  radius (0.25 m).

Our decision rules turn these into a function of a finished :class:`EpisodeRecord`. They are
applied in this order and the first that matches decides, so success plus the five failures
partition all episodes. "Near" an object means a geodesic distance strictly below the stop
radius (1 m) to one of its view points, the measure success uses; the facts about a stop come
from :mod:`vlln.tasks.stop`. docs/metrics.md gives the reasons for each rule and the
hand-checked episodes they are tested against.

1. **success** -- stopped strictly closer than the success radius (0.25 m) to a goal's view
   point.
2. Not stopped (step, look or talk cap, or an error): **MD** if the target was observed
   (``target_seen_step`` is set), else **Expl**.

A stop outside the success radius:

3. **ST** -- near the target (final geodesic distance below 1 m), unless the stop is at a
   distractor: facing a same-category instance that is not a goal, or nearer to a
   distractor's view points than to the target's (then the rules below decide).
4. The agent stopped because nothing was left to explore (``stop_reason`` is
   ``explored``): it did not stop *at* anything, so **MD** if it observed the target, else
   **Expl**.
5. **ST** -- facing a goal instance (``stop_instance_id in target_ids``) from farther away:
   the right object was found and the agent stopped short. On ObjectNav every instance of the
   category is a goal, so a stop at any of them lands here or in rules 1 and 3.
6. **AD** -- facing a same-category instance that is not a goal.
7. **AD** -- near a same-category distractor (``distractor_distance`` below 1 m) while facing
   something else or nothing: small or high objects (a bottle on a sill, a ceiling light)
   are often out of the level view of an agent standing at them.
8. **WD** -- facing an object of another category.
9. A stop at nothing identifiable, far from the target and every distractor: **MD** if the
   target was observed, else **Expl**.

Old records without ``stop_reason`` or ``distractor_distance`` (written before these
fields) skip rules 4 and 7 and the nearer-distractor test of rule 3; the other rules apply to
them unchanged. Agents that do not report a stop reason (all but the frontier agent) skip
rule 4.

"Observed" has one definition, :func:`target_observed`, which the runner uses to fill
``target_seen_step``: the target instance covers at least :data:`OBSERVE_MIN_PIXELS` pixels of
a 640x480 instance-id image (scaled by image area at other resolutions, see
:func:`observe_min_pixels`) and the nearest point of its box is at most
:data:`OBSERVE_MAX_DISTANCE` metres from the camera (straight line).
"""

from __future__ import annotations

import math

from vlln.errors import ConfigError
from vlln.tasks.metrics import SUCCESS_RADIUS, require_radius, success
from vlln.tasks.record import EpisodeRecord, StopReason
from vlln.world.catalogue.aliases import canonical_category

SUCCESS = "success"
STOP_FAILURE = "stop_failure"
AMBIGUOUS_DETECTION = "ambiguous_detection"
WRONG_DETECTION = "wrong_detection"
MISSED_DETECTION = "missed_detection"
EXPLORATION_FAILURE = "exploration_failure"

FAILURE_CLASSES: tuple[str, ...] = (
    SUCCESS,
    STOP_FAILURE,
    AMBIGUOUS_DETECTION,
    WRONG_DETECTION,
    MISSED_DETECTION,
    EXPLORATION_FAILURE,
)
"""Every outcome class, success first, in the order the rules are applied."""

CLASS_ABBREVIATIONS: dict[str, str] = {
    SUCCESS: "SR",
    STOP_FAILURE: "ST",
    AMBIGUOUS_DETECTION: "AD",
    WRONG_DETECTION: "WD",
    MISSED_DETECTION: "MD",
    EXPLORATION_FAILURE: "Expl",
}
"""The paper's short names, for table headers."""

STOP_RADIUS = 1.0
"""Metres; a stop closer than this but not a success is a stop failure."""

OBSERVE_MIN_PIXELS = 200
"""Target pixels needed in a 640x480 instance-id image to count the target as observed."""

OBSERVE_MAX_DISTANCE = 5.0
"""Metres from the camera to the nearest point of the target's box, at most."""

_REFERENCE_IMAGE_AREA = 640 * 480


def observe_min_pixels(width: int, height: int) -> int:
    """Pixels the target must cover in a ``width`` x ``height`` image (area-scaled, >= 1)."""
    if width <= 0 or height <= 0:
        raise ConfigError(f"image size must be positive, got {width}x{height}")
    scaled = math.ceil(OBSERVE_MIN_PIXELS * width * height / _REFERENCE_IMAGE_AREA)
    return max(1, scaled)


def target_observed(pixel_count: int, distance: float, width: int, height: int) -> bool:
    """THE rule for "the agent observed the target" in one frame.

    ``pixel_count`` is the number of pixels of the target instance in the instance-id image of
    size ``width`` x ``height``; ``distance`` the straight-line distance in metres from the
    camera to the nearest point of the target's box.
    """
    if pixel_count < 0:
        raise ConfigError(f"pixel_count must be >= 0, got {pixel_count}")
    return pixel_count >= observe_min_pixels(width, height) and distance <= OBSERVE_MAX_DISTANCE


def classify(
    record: EpisodeRecord,
    success_radius: float = SUCCESS_RADIUS,
    stop_radius: float = STOP_RADIUS,
) -> str:
    """The one class of :data:`FAILURE_CLASSES` this episode falls into (rules: module doc)."""
    require_radius("stop_radius", stop_radius)
    if stop_radius < success_radius:
        raise ConfigError(
            f"stop_radius ({stop_radius} m) must not be smaller than success_radius "
            f"({success_radius} m): a stop failure lies between the two"
        )
    if success(record, success_radius):
        return SUCCESS
    seen = record.target_seen_step is not None
    if not record.stopped:
        return MISSED_DETECTION if seen else EXPLORATION_FAILURE
    facing_goal = (
        record.stop_instance_id is not None and record.stop_instance_id in record.target_ids
    )
    facing_distractor = not facing_goal and _same_category(
        record.stop_instance_category, record.object_category
    )
    near = record.distractor_distance
    nearer_distractor = near is not None and near < record.geodesic_final
    if record.geodesic_final < stop_radius and not (facing_distractor or nearer_distractor):
        return STOP_FAILURE
    if record.stop_reason == StopReason.EXPLORED:
        return MISSED_DETECTION if seen else EXPLORATION_FAILURE
    if facing_goal:
        return STOP_FAILURE
    if facing_distractor or (near is not None and near < stop_radius):
        return AMBIGUOUS_DETECTION
    if record.stop_instance_category is not None:
        return WRONG_DETECTION
    return MISSED_DETECTION if seen else EXPLORATION_FAILURE


def _same_category(seen: str | None, target: str) -> bool:
    return seen is not None and _canonical(seen) == _canonical(target)


def _canonical(category: str) -> str:
    return canonical_category(category.strip().lower())
