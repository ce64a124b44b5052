"""The failure taxonomy of VL-LN Bench: every episode is a success or exactly one failure.

The paper names five failure modes (missed detection, wrong detection, ambiguous detection,
exploration failure, stop failure) without decision rules. Ours are applied in this order to
a finished :class:`EpisodeRecord`; the first rule that matches decides, so success plus the
five failures partition all episodes:

1. **success** -- stopped strictly closer than the success radius (0.25 m) to a view point.
2. **stop_failure** (ST) -- stopped with the final geodesic distance below the stop radius
   (1.0 m): near the target but outside the success radius.
3. **stop_failure** (ST) as well -- stopped farther away while the object it stopped at is a
   goal instance (``stop_instance_id in target_ids``; the environment records a visible goal
   within 1.5 m first, then a same-category instance, then the nearest visible object): the
   right object was found and the agent stopped too early. For ObjectNav every instance of
   the category is a goal, so a stop at any instance of the category lands here or in rules
   1-2, never in rule 4.
4. **ambiguous_detection** (AD) -- stopped facing an instance of the target category that is
   not a goal: a same-category distractor (IIGN/IGN only, see rule 3).
5. **wrong_detection** (WD) -- stopped otherwise: facing an object of another category, or
   nothing identifiable (``stop_instance_category`` is ``None``).
6. **missed_detection** (MD) -- did not stop (step, look or talk cap, or an error) although
   the target was observed (``target_seen_step`` is set).
7. **exploration_failure** (Expl) -- did not stop and never observed the target.

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
from vlln.tasks.record import EpisodeRecord

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
    if record.stopped:
        if record.geodesic_final < stop_radius:
            return STOP_FAILURE
        if record.stop_instance_id is not None and record.stop_instance_id in record.target_ids:
            return STOP_FAILURE
        if _same_category(record.stop_instance_category, record.object_category):
            return AMBIGUOUS_DETECTION
        return WRONG_DETECTION
    if record.target_seen_step is not None:
        return MISSED_DETECTION
    return EXPLORATION_FAILURE


def _same_category(seen: str | None, target: str) -> bool:
    return seen is not None and seen.strip().lower() == target.strip().lower()
