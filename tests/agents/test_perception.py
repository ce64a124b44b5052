"""The frontier agent's detectors: the noise model's statistics, its tables and its seeding."""

from __future__ import annotations

import numpy as np
import pytest

from vlln.agents.frontier.perception import (
    DETECTORS,
    GroundTruthDetector,
    NoiseModel,
    NoisyDetector,
    make_detector,
)
from vlln.agents.frontier.perception.confusions import (
    COLOR_LOOKALIKES,
    LOOKALIKE_GROUPS,
    MATERIAL_LOOKALIKES,
    category_lookalikes,
)
from vlln.errors import ConfigError
from vlln.tasks.env import DetectedObject
from vlln.world.catalogue import default_catalogue
from vlln.world.materials import COLORS, MATERIAL_TEXTURE, MATERIALS
from vlln.world.model import Attributes

DISTANCES = (1.0, 3.0, 5.0, 7.0)
AREAS = (100, 400, 1600)


def _chairs(count: int) -> dict[int, DetectedObject]:
    red_wooden = Attributes(color="red", material="wood", texture="grained", size="small")
    return {i: DetectedObject("chair", red_wooden) for i in range(1, count + 1)}


def _scene() -> tuple[np.ndarray, np.ndarray, dict[int, tuple[float, int]]]:
    """One frame holding an instance for every (distance, area): its id -> (distance, area)."""
    ids = np.full((120, 160), -1, np.int32)  # walls everywhere else
    depth = np.full((120, 160), 9.0, np.float32)
    truth: dict[int, tuple[float, int]] = {}
    row = 0
    for distance in DISTANCES:
        for area in AREAS:
            instance = len(truth) + 1
            flat_ids, flat_depth = ids.reshape(-1), depth.reshape(-1)
            flat_ids[row : row + area] = instance
            flat_depth[row : row + area] = distance
            truth[instance] = (distance, area)
            row += area
    return ids, depth, truth


def test_recall_falls_with_distance_and_apparent_size_as_the_formula_says() -> None:
    ids, depth, truth = _scene()
    detector = NoisyDetector(_chairs(len(truth)), seed=[7])
    frames = 2000
    hits = dict.fromkeys(truth, 0)
    for _ in range(frames):
        seen = np.unique(detector.detect(ids, depth, pixel_area=1))
        for instance in seen[seen > 0].tolist():
            hits[instance] += 1
    rate = {truth[i]: hits[i] / frames for i in truth}
    model = NoiseModel()
    for (distance, area), measured in rate.items():
        expected = float(model.recall(np.array([distance]), np.array([float(area)]))[0])
        assert abs(measured - expected) < 0.035, (distance, area, measured, expected)
    for area in AREAS:  # farther is never easier, and 7 m is much harder than 1 m
        by_distance = [rate[(d, area)] for d in DISTANCES]
        assert by_distance == sorted(by_distance, reverse=True)
        assert by_distance[-1] < 0.25 * by_distance[0]
    for distance in DISTANCES[:3]:
        by_area = [rate[(distance, a)] for a in AREAS]
        assert by_area == sorted(by_area)


def test_missed_instances_are_blanked_and_structure_kept() -> None:
    ids, depth, truth = _scene()
    detector = NoisyDetector(_chairs(len(truth)), seed=[1])
    out = detector.detect(ids, depth, pixel_area=1)
    assert out.shape == ids.shape and out.dtype == ids.dtype
    assert np.array_equal(out[ids < 0], ids[ids < 0])
    kept = (out == ids) | (out == 0)
    assert kept.all()
    assert set(np.unique(out[out > 0]).tolist()) < set(truth)  # some far ones are missed


def test_confusions_follow_the_table_at_the_configured_rate() -> None:
    count = 4000
    labels = NoisyDetector(_chairs(count), seed=[3]).labels
    lookalikes = category_lookalikes("chair")
    assert set(lookalikes) == {"armchair", "stool"}
    reported = [label.category for label in labels.values()]
    assert set(reported) == {"chair", *lookalikes}
    confused = sum(category != "chair" for category in reported) / count
    assert abs(confused - NoiseModel().confusion_rate) < 0.02
    for other in lookalikes:  # each look-alike equally likely
        share = reported.count(other) / count
        assert abs(share - NoiseModel().confusion_rate / len(lookalikes)) < 0.02
    colours = [label.attributes.color for label in labels.values()]
    assert set(colours) == {"red", *COLOR_LOOKALIKES["red"]}
    assert abs(sum(c != "red" for c in colours) / count - NoiseModel().color_error_rate) < 0.02
    for label in labels.values():  # a misread material brings its own texture word
        assert label.attributes.texture == MATERIAL_TEXTURE[label.attributes.material]
        assert label.attributes.material in ("wood", *MATERIAL_LOOKALIKES["wood"])


def test_a_category_without_lookalikes_is_never_confused() -> None:
    truth = {i: DetectedObject("piano", Attributes()) for i in range(1, 500)}
    assert category_lookalikes("piano") == ()
    labels = NoisyDetector(truth, seed=[0]).labels
    assert {label.category for label in labels.values()} == {"piano"}
    assert {label.attributes for label in labels.values()} == {Attributes()}


def test_tables_name_catalogue_categories_colours_and_materials() -> None:
    names = set(default_catalogue().names)
    for group in LOOKALIKE_GROUPS:
        assert set(group) <= names, set(group) - names
    assert set(COLOR_LOOKALIKES) == set(COLORS)
    assert all(set(near) <= set(COLORS) for near in COLOR_LOOKALIKES.values())
    assert "dark brown" in COLOR_LOOKALIKES["brown"]  # nearest in RGB, not alphabetical
    assert set(MATERIAL_LOOKALIKES) == set(MATERIALS)
    assert all(set(m) <= set(MATERIALS) for m in MATERIAL_LOOKALIKES.values())
    for category in names:  # symmetric: if a is taken for b, b may be taken for a
        for other in category_lookalikes(category):
            assert category in category_lookalikes(other)


def test_same_seed_same_detections_another_seed_others() -> None:
    ids, depth, truth = _scene()

    def frames(seed: int) -> tuple[list[bytes], dict[int, DetectedObject]]:
        detector = NoisyDetector(_chairs(len(truth)), seed=[seed, 99])
        return [detector.detect(ids, depth, 1).tobytes() for _ in range(30)], dict(detector.labels)

    assert frames(5) == frames(5)
    assert frames(5)[0] != frames(6)[0]


def test_the_ground_truth_detector_reports_everything_as_it_is() -> None:
    ids, depth, truth = _scene()
    chairs = _chairs(len(truth))
    detector = make_detector("truth", chairs, [0])
    assert isinstance(detector, GroundTruthDetector) and detector.labels == chairs
    assert detector.detect(ids, depth, 1) is ids
    assert isinstance(make_detector("noisy", chairs, [0]), NoisyDetector)
    assert DETECTORS == ("truth", "noisy")
    with pytest.raises(ConfigError, match="unknown detector 'yolo'; choose one of: truth, noisy"):
        make_detector("yolo", chairs, [0])
    with pytest.raises(ConfigError, match="confusion_rate"):
        NoiseModel(confusion_rate=1.5)
