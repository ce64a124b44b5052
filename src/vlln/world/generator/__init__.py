"""The procedural house generator: seeded houses whose ground truth is known exactly."""

from vlln.world.generator.house import generate_house
from vlln.world.generator.params import (
    HouseParameters,
    ParameterInfo,
    describe_parameters,
    parameters_from_overrides,
)

__all__ = [
    "HouseParameters",
    "ParameterInfo",
    "describe_parameters",
    "generate_house",
    "parameters_from_overrides",
]
