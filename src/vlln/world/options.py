"""The ``--preset`` setting (which houses a seed gives) as a config class that the configs of
the commands building procedural houses inherit."""

from __future__ import annotations

from pydantic import field_validator

from vlln.config import Config
from vlln.world.generator.presets import DEFAULT_PRESET, PRESETS


class PresetOptions(Config):
    """Which houses: the benchmark's preset unless told."""

    preset: str = DEFAULT_PRESET
    """houses: mp3d (the benchmark's, calibrated to Matterport3D) or small (demo, fast tests)"""

    @field_validator("preset")
    @classmethod
    def _known_preset(cls, value: str | None) -> str | None:
        if value is not None and value not in PRESETS:
            raise ValueError(f"unknown house preset {value!r}; choose one of: {', '.join(PRESETS)}")
        return value


class GeneratorPresetOptions(PresetOptions):
    """:class:`PresetOptions` where no preset means the generator's own parameters."""

    preset: str | None = None  # type: ignore[assignment]
    """houses: mp3d (the benchmark's, calibrated to Matterport3D) or small (demo, fast tests);
    none: the generator's parameters"""
