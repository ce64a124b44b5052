"""Tests of house-generator parameters: validation messages and the parameter listing."""

from __future__ import annotations

from dataclasses import fields

import pytest

from vlln.errors import HouseParametersError
from vlln.world.generator import HouseParameters, describe_parameters, generate_house


def test_defaults_are_valid() -> None:
    HouseParameters().validate()


@pytest.mark.parametrize(
    ("params", "named", "hint"),
    [
        (HouseParameters(min_rooms=8, max_rooms=5), "min_rooms=8", "max_rooms=5"),
        (HouseParameters(min_rooms=0), "min_rooms=0", "[1, 40]"),
        (HouseParameters(max_rooms=41), "max_rooms=41", "[1, 40]"),
        (HouseParameters(min_rooms=2.5), "min_rooms=2.5", "whole number"),  # type: ignore[arg-type]
        (HouseParameters(min_area=300.0, max_area=100.0), "min_area=300", "max_area=100"),
        (
            HouseParameters(min_rooms=12, max_rooms=12, min_area=50.0, max_area=60.0),
            "max_area=60",
            "raise max_area to >= 84",
        ),
        (HouseParameters(min_rooms=1, max_rooms=2, min_area=200.0), "min_area=200", "max_rooms"),
        (HouseParameters(ceiling_height=1.9), "ceiling_height=1.9", "[2.3, 4]"),
        (HouseParameters(wall_thickness=0.0), "wall_thickness=0", "[0.05, 0.25]"),
        (HouseParameters(door_width=0.6), "door_width=0.6", "0.36 m wide agent"),
        (HouseParameters(door_width=1.5), "door_width=1.5", "shortest room side"),
        (HouseParameters(clutter=-1.0), "clutter=-1", "[0, 3]"),
        (HouseParameters(clutter=float("nan")), "clutter=nan", "number"),
    ],
)
def test_bad_parameters_name_the_parameter_and_the_fix(
    params: HouseParameters, named: str, hint: str
) -> None:
    with pytest.raises(HouseParametersError) as raised:
        params.validate()
    message = str(raised.value)
    assert named in message
    assert hint in message


def test_generate_house_validates_before_drawing() -> None:
    with pytest.raises(HouseParametersError, match="min_rooms=9"):
        generate_house(0, HouseParameters(min_rooms=9, max_rooms=3))
    with pytest.raises(HouseParametersError, match="seed"):
        generate_house(-1)


def test_describe_parameters_lists_every_field_with_help() -> None:
    described = describe_parameters()
    assert [p.name for p in described] == [f.name for f in fields(HouseParameters)]
    defaults = HouseParameters()
    for info in described:
        assert info.help
        assert info.default == getattr(defaults, info.name)
