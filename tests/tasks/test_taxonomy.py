from __future__ import annotations

import math
from collections import Counter
from dataclasses import replace

import numpy as np
import pytest

from tests.tasks.test_metrics import make_record
from vlln.errors import ConfigError
from vlln.tasks.metrics import success
from vlln.tasks.record import EndReason, EpisodeRecord, StopReason
from vlln.tasks.taxonomy import (
    AMBIGUOUS_DETECTION,
    EXPLORATION_FAILURE,
    FAILURE_CLASSES,
    MISSED_DETECTION,
    OBSERVE_MAX_DISTANCE,
    OBSERVE_MIN_PIXELS,
    STOP_FAILURE,
    SUCCESS,
    WRONG_DETECTION,
    classify,
    observe_min_pixels,
    target_observed,
)

STOP = EndReason.STOP.value


def test_classes_are_six_with_success_first() -> None:
    assert FAILURE_CLASSES[0] == SUCCESS
    assert len(set(FAILURE_CLASSES)) == 6


def test_success() -> None:
    assert classify(make_record()) == SUCCESS


def test_stop_failure_near_target() -> None:
    # Exactly at the success radius is not a success but a stop failure.
    assert classify(make_record(geodesic_trace=[2.0, 0.25])) == STOP_FAILURE
    assert classify(make_record(geodesic_trace=[2.0, 0.99])) == STOP_FAILURE
    # Near the target, an object of another category in view does not matter.
    near_table = make_record(
        geodesic_trace=[2.0, 0.6], stop_instance_id=9, stop_instance_category="table"
    )
    assert classify(near_table) == STOP_FAILURE
    # Nor does a distractor that is farther than the target.
    assert classify(replace(near_table, distractor_distance=0.6)) == STOP_FAILURE


def test_near_the_target_but_at_a_distractor_is_ambiguous() -> None:
    # Facing a same-category distractor that stands beside the target.
    facing = make_record(geodesic_trace=[2.0, 0.6], stop_instance_id=9)
    assert classify(facing) == AMBIGUOUS_DETECTION
    # Facing nothing, but nearer to a distractor's view points than to the target's.
    nearer = make_record(
        geodesic_trace=[2.0, 0.6],
        stop_instance_id=None,
        stop_instance_category=None,
        distractor_distance=0.1,
    )
    assert classify(nearer) == AMBIGUOUS_DETECTION


def test_stop_failure_facing_target_from_afar() -> None:
    record = make_record(geodesic_trace=[3.0, 2.0])  # stop_instance_id 7 is the target
    assert classify(record) == STOP_FAILURE


def test_stop_radius_is_a_setting() -> None:
    record = make_record(
        geodesic_trace=[2.0, 1.5], stop_instance_id=9, stop_instance_category="table"
    )
    assert classify(record) == WRONG_DETECTION
    assert classify(record, stop_radius=2.0) == STOP_FAILURE
    # "Near a distractor" uses the same radius.
    near = replace(
        record,
        geodesic_trace=[9.0],
        stop_instance_id=None,
        stop_instance_category=None,
        distractor_distance=1.5,
    )
    assert classify(near) == MISSED_DETECTION
    assert classify(near, stop_radius=2.0) == AMBIGUOUS_DETECTION


def test_ambiguous_detection_same_category_distractor() -> None:
    record = make_record(geodesic_trace=[3.0, 1.0], stop_instance_id=9)  # exactly 1 m
    assert classify(record) == AMBIGUOUS_DETECTION
    shouted = make_record(geodesic_trace=[4.0], stop_instance_id=9, stop_instance_category="Chair")
    assert classify(shouted) == AMBIGUOUS_DETECTION
    alias = make_record(
        object_category="couch",
        geodesic_trace=[4.0],
        stop_instance_id=9,
        stop_instance_category="sofa",
    )
    assert classify(alias) == AMBIGUOUS_DETECTION


def test_ambiguous_detection_standing_at_a_distractor() -> None:
    facing_wall = make_record(
        geodesic_trace=[6.0], stop_instance_id=None, stop_instance_category=None
    )
    assert classify(replace(facing_wall, distractor_distance=0.99)) == AMBIGUOUS_DETECTION
    assert classify(replace(facing_wall, distractor_distance=1.0)) == MISSED_DETECTION  # seen
    facing_table = replace(facing_wall, stop_instance_id=3, stop_instance_category="table")
    assert classify(replace(facing_table, distractor_distance=0.5)) == AMBIGUOUS_DETECTION
    assert classify(replace(facing_table, distractor_distance=None)) == WRONG_DETECTION


def test_objectnav_same_category_stop_is_never_ambiguous() -> None:
    record = make_record(
        task="objectnav", target_ids=[7, 9, 11], geodesic_trace=[4.0, 2.5], stop_instance_id=9
    )
    assert classify(record) == STOP_FAILURE


def test_wrong_detection_needs_an_object_of_another_category() -> None:
    other = make_record(geodesic_trace=[4.0], stop_instance_id=3, stop_instance_category="sofa")
    assert classify(other) == WRONG_DETECTION
    unseen = replace(other, target_seen_step=None)
    assert classify(unseen) == WRONG_DETECTION  # it stopped at the sofa all the same
    unreachable = replace(other, geodesic_trace=[math.inf])
    assert classify(unreachable) == WRONG_DETECTION


def test_stop_at_nothing_is_missed_or_exploration() -> None:
    nothing = make_record(geodesic_trace=[4.0], stop_instance_id=None, stop_instance_category=None)
    assert classify(nothing) == MISSED_DETECTION  # target_seen_step 2
    assert classify(replace(nothing, target_seen_step=None)) == EXPLORATION_FAILURE
    unreachable = replace(nothing, geodesic_trace=[math.inf], target_seen_step=None)
    assert classify(unreachable) == EXPLORATION_FAILURE


def test_nothing_left_to_explore_is_exploration_or_missed() -> None:
    gave_up = make_record(
        geodesic_trace=[6.0],
        stop_instance_id=3,
        stop_instance_category="sofa",
        target_seen_step=None,
        stop_reason=StopReason.EXPLORED.value,
        distractor_distance=0.4,
    )
    assert classify(gave_up) == EXPLORATION_FAILURE  # not WD, not AD: it stopped at nothing
    assert classify(replace(gave_up, target_seen_step=12)) == MISSED_DETECTION
    # Within 1 m of the target a stop is a stop failure whatever the reason.
    assert classify(replace(gave_up, geodesic_trace=[0.7], distractor_distance=None)) == (
        STOP_FAILURE
    )
    # The same stop made at a candidate is a detection failure.
    at_candidate = replace(gave_up, stop_reason=StopReason.CANDIDATE.value)
    assert classify(at_candidate) == AMBIGUOUS_DETECTION


@pytest.mark.parametrize("reason", [r.value for r in EndReason if r is not EndReason.STOP])
def test_missed_detection_when_seen_but_not_stopped(reason: str) -> None:
    record = make_record(end_reason=reason, geodesic_trace=[3.0, 0.1], target_seen_step=1)
    assert classify(record) == MISSED_DETECTION


@pytest.mark.parametrize("reason", [r.value for r in EndReason if r is not EndReason.STOP])
def test_exploration_failure_when_never_seen(reason: str) -> None:
    record = make_record(end_reason=reason, geodesic_trace=[9.0, 8.0], target_seen_step=None)
    assert classify(record) == EXPLORATION_FAILURE


def test_seen_step_zero_counts_as_seen() -> None:
    record = make_record(end_reason=EndReason.STEP_CAP.value, target_seen_step=0)
    assert classify(record) == MISSED_DETECTION


def test_classify_rejects_inconsistent_radii() -> None:
    with pytest.raises(ConfigError, match="stop_radius"):
        classify(make_record(), success_radius=1.0, stop_radius=0.5)
    with pytest.raises(ConfigError, match="stop_radius"):
        classify(make_record(), stop_radius=-1.0)


def random_record(rng: np.random.Generator, index: int) -> EpisodeRecord:
    steps = int(rng.integers(0, 6))
    trace = [float(d) for d in rng.choice([0.0, 0.1, 0.25, 0.5, 1.0, 2.0, 7.0, math.inf], steps)]
    seen = int(rng.integers(0, 5)) if rng.random() < 0.5 else None
    stop_id = [None, 7, 8, 9][int(rng.integers(0, 4))]
    stop_category = {None: None, 7: "chair", 8: "chair", 9: "sofa"}[stop_id]
    task = str(rng.choice(["iign", "ign", "objectnav"]))
    near = [None, 0.0, 0.5, 0.99, 1.0, 3.0][int(rng.integers(0, 6))]
    return make_record(
        episode_id=str(index),
        task=task,
        # On ObjectNav every chair is a goal, so there is no distractor to be near.
        target_ids=[7, 8] if task == "objectnav" else [7],
        end_reason=str(rng.choice([r.value for r in EndReason])),
        steps=steps,
        geodesic_start=float(rng.choice([0.0, 3.0, math.inf])),
        geodesic_trace=trace,
        stop_instance_id=stop_id,
        stop_instance_category=stop_category,
        target_seen_step=seen,
        stop_reason=[None, *(r.value for r in StopReason)][int(rng.integers(0, 3))],
        distractor_distance=None if task == "objectnav" else near,
    )


def test_classes_partition_random_records() -> None:
    rng = np.random.default_rng(1234)
    records = [random_record(rng, i) for i in range(3000)]
    labels = [classify(record) for record in records]
    counts = Counter(labels)
    assert set(counts) <= set(FAILURE_CLASSES)
    assert sum(counts.values()) == len(records)
    assert set(counts) == set(FAILURE_CLASSES)  # the generator reaches every class
    for record, label in zip(records, labels, strict=True):
        assert (label == SUCCESS) == success(record)
        facing_distractor = record.stop_instance_category == "chair" and (
            record.stop_instance_id not in record.target_ids
        )
        near = record.distractor_distance
        if not record.stopped:
            assert label in (MISSED_DETECTION, EXPLORATION_FAILURE)
        if label in (STOP_FAILURE, AMBIGUOUS_DETECTION, WRONG_DETECTION):
            assert record.stopped
        if label in (AMBIGUOUS_DETECTION, WRONG_DETECTION):
            assert record.stop_reason != StopReason.EXPLORED  # giving up is not a detection
        if label == MISSED_DETECTION:
            assert record.target_seen_step is not None
        if label == EXPLORATION_FAILURE:
            assert record.target_seen_step is None
        if label == STOP_FAILURE:
            assert record.geodesic_final < 1.0 or record.stop_instance_id in record.target_ids
        if label == AMBIGUOUS_DETECTION:
            assert record.task != "objectnav"
            assert facing_distractor or (near is not None and near < 1.0)
        if label == WRONG_DETECTION:
            assert record.stop_instance_category == "sofa"
            assert near is None or near >= 1.0


def test_observe_min_pixels_scales_with_area() -> None:
    assert observe_min_pixels(640, 480) == OBSERVE_MIN_PIXELS == 200
    assert observe_min_pixels(320, 240) == 50
    assert observe_min_pixels(1280, 960) == 800
    assert observe_min_pixels(384, 384) == 96  # 200 * 147456 / 307200
    assert observe_min_pixels(10, 10) == 1
    with pytest.raises(ConfigError, match="image size"):
        observe_min_pixels(0, 480)


def test_target_observed_rule() -> None:
    assert target_observed(200, 5.0, 640, 480)
    assert not target_observed(199, 1.0, 640, 480)
    assert not target_observed(5000, OBSERVE_MAX_DISTANCE + 0.01, 640, 480)
    assert target_observed(50, 2.0, 320, 240)
    assert not target_observed(49, 2.0, 320, 240)
    assert not target_observed(300, math.nan, 640, 480)
    with pytest.raises(ConfigError, match="pixel_count"):
        target_observed(-1, 1.0, 640, 480)
