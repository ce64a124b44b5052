"""``--preset``: a known preset or one line naming the valid ones."""

from __future__ import annotations

import pytest

from vlln.errors import ConfigError
from vlln.world.generator.presets import DEFAULT_PRESET
from vlln.world.options import GeneratorPresetOptions, PresetOptions


def test_the_preset_defaults_to_the_benchmarks_and_unknown_ones_are_refused() -> None:
    assert PresetOptions.build({}).preset == DEFAULT_PRESET
    assert GeneratorPresetOptions.build({}).preset is None
    assert GeneratorPresetOptions.build({"preset": "small"}).preset == "small"
    with pytest.raises(ConfigError, match=r"^--preset: unknown house preset 'tiny'; choose one"):
        GeneratorPresetOptions.build({"preset": "tiny"})
