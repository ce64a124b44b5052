"""What Matterport3D, as VL-LN Bench uses it, looks like: the statistics our houses are held to.

Each anchor is one figure per building (or per scene or episode) with the band we accept for the
mean of a preset's houses and the source it comes from. docs/world-statistics.md gives every
source, says which figures are direct and which derived, and justifies each band; most bands are
the anchor plus or minus two standard errors of a 20-house mean given MP3D's spread between
buildings. ``compare`` puts measured figures beside the anchors for ``vlln bench world``.
"""

from __future__ import annotations

from dataclasses import dataclass

from vlln.errors import ConfigError


@dataclass(frozen=True)
class Anchor:
    """One statistic of MP3D as VL-LN uses it, with the band a preset's mean must fall in."""

    name: str
    value: float
    low: float
    high: float
    unit: str
    source: str


ANCHORS: tuple[Anchor, ...] = (
    Anchor(
        "regions_per_building",
        22.84,
        16.6,
        29.1,
        "regions",
        "HM3DSem paper (arXiv 2210.05633) Table 1, MP3D row: 2,056 rooms in 90 scenes",
    ),
    Anchor(
        "navigable_area_m2",
        338.0,
        245.0,
        430.0,
        "m2",
        "HM3D paper (arXiv 2109.08238) abstract: HM3D's 112.5k m2 navigable is 3.7x MP3D; /90",
    ),
    Anchor(
        "floors_per_building",
        2.2,
        1.7,
        2.7,
        "storeys",
        "Matterport3DSimulator connectivity/*.json (90 buildings): storeys under the panoramas",
    ),
    Anchor(
        "instances_per_scene",
        227.5,
        165.0,
        290.0,
        "instances",
        "VL-LN paper, Data Statistics: 20,476 annotated instances in 90 MP3D scenes",
    ),
    Anchor(
        "instances_per_category",
        3.0,
        2.0,
        4.0,
        "instances",
        "MP3D category_mapping.tsv counts (Poisson estimate 3.6) and real .house files (2.0, 3.8)",
    ),
    Anchor(
        "distractor_share",
        0.80,
        0.65,
        0.95,
        "of episodes",
        "real .house files GdvgFV5R1Z5 0.72, YmJkqBEsHnH 0.88; category_mapping.tsv estimate 0.89",
    ),
    Anchor(
        "distractors_per_target",
        9.24,
        6.5,
        12.0,
        "instances",
        "MP3D category_mapping.tsv counts, 112 most frequent categories, Poisson over 90 "
        "buildings: sum(rate^2) / sum(rate) same-category others per instance",
    ),
    Anchor(
        "start_to_target_geodesic_m",
        18.6,
        14.0,
        23.3,
        "m",
        "Matterport3DSimulator connectivity graphs: mean walk between two places, 90 buildings",
    ),
    Anchor(
        "start_poses_per_scene",
        42.0,
        38.0,
        46.0,
        "poses",
        "VL-LN paper, Data Statistics (42 per scene) and supplementary (3,785 poses / 90 scenes)",
    ),
    Anchor(
        "test_episodes",
        500.0,
        500.0,
        500.0,
        "episodes",
        "VL-LN paper, Data Statistics: 246,433 / 86,386 / 500 train / val / test episodes",
    ),
    Anchor(
        "test_scenes",
        14.0,
        14.0,
        14.0,
        "scenes",
        "VL-LN paper, Data Statistics: scenes split 61/15/14 following VLN-CE",
    ),
)


def anchor(name: str) -> Anchor:
    """The anchor called ``name``; a ConfigError lists the known names otherwise."""
    for candidate in ANCHORS:
        if candidate.name == name:
            return candidate
    known = ", ".join(a.name for a in ANCHORS)
    raise ConfigError(f"no anchor called {name!r}; known anchors: {known}")


def compare(measured: dict[str, float]) -> list[dict[str, object]]:
    """One row per anchor: the measured figure (None if not measured), the anchor, its band, and
    whether the figure lies in the band (None if not measured). Unknown names are an error, so a
    misspelt statistic cannot silently go unchecked."""
    for name in measured:
        anchor(name)
    rows: list[dict[str, object]] = []
    for a in ANCHORS:
        value = measured.get(a.name)
        rows.append(
            {
                "name": a.name,
                "measured": value,
                "anchor": a.value,
                "low": a.low,
                "high": a.high,
                "unit": a.unit,
                "within": None if value is None else a.low <= value <= a.high,
                "source": a.source,
            }
        )
    return rows
