"""``vlln eval --config run.json`` replays a run: the same files, byte for byte; a flag given
overrides its stored setting and nothing else. Agent options are typed and round-trip through
run.json, old string-valued ones included."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from vlln.agents.model.options import OpenAIVLMOptions
from vlln.cli import main
from vlln.cli.eval_configs import EvalCommand
from vlln.errors import ConfigError
from vlln.eval.config import EvalConfig

pytestmark = pytest.mark.slow  # plays whole episodes or trains a model

RUN_FILES = ("episodes.jsonl", "run.json", "summary.json", "summary.md")


def run_files(folder: Path) -> dict[str, bytes]:
    return {name: (folder / name).read_bytes() for name in RUN_FILES}


def test_a_replayed_run_is_the_same_byte_for_byte_and_a_flag_changes_only_its_setting(
    tmp_path: Path, split_cache: Path
) -> None:
    first = tmp_path / "first"
    common = ["--cache-dir", str(split_cache), "--quiet"]
    args = ["eval", "--agent", "frontier", "--task", "iign", "--preset", "small"]
    args += ["--houses", "1", "--episodes", "2", "--budgets", "0,2", "--max-steps", "60"]
    assert main([*args, *common, "--out", str(first)]) == 0
    stored = first / "run.json"
    again = tmp_path / "again"
    assert main(["eval", "--config", str(stored), "--out", str(again), *common]) == 0
    assert run_files(again) == run_files(first)

    seeded = tmp_path / "seeded"
    replay = ["eval", "--config", str(stored), "--seed", "1", "--stop-after", "0"]
    assert main([*replay, "--out", str(seeded), *common]) == 0
    before, after = json.loads(stored.read_text()), json.loads((seeded / "run.json").read_text())
    assert (before["seed"], after["seed"]) == (0, 1)
    assert {**after, "seed": 0} == before


def test_a_replay_takes_budget_over_the_stored_budgets_and_refuses_both(tmp_path: Path) -> None:
    stored = EvalConfig(agent="expert", task="iign", budgets=(0, 1), preset="small").to_json()
    replayed = EvalCommand.build(EvalCommand.replay(stored, "run.json", {"budget": 3, "out": "o"}))
    assert replayed.run_settings().budgets == (3,)
    with pytest.raises(ConfigError, match=r"^give --budget or --budgets, not both$"):
        EvalCommand.build({**stored, "budget": 3, "out": "o"})


OLD_OPTIONS = {"base_url": "http://127.0.0.1:9/v1", "model": "m", "timeout_s": "0.5"}
"""openai-vlm options as run.json stored them before they were typed (all strings)."""


def test_openai_vlm_options_round_trip_through_run_json_typed() -> None:
    old = {
        **EvalConfig(agent="expert", task="iign", preset="small").to_json(),
        "agent": "openai-vlm",
        "agent_options": OLD_OPTIONS,
    }
    config = EvalConfig.from_json(old, "run.json")
    options = config.agent_options
    assert isinstance(options, OpenAIVLMOptions)
    assert (options.timeout_s, options.max_retries) == (0.5, 4)  # the class's default retries
    stored: dict[str, Any] = json.loads(json.dumps(config.to_json()))
    # Only the options given are stored, sorted, as JSON values of their types.
    assert stored["agent_options"] == {**OLD_OPTIONS, "timeout_s": 0.5}
    assert list(stored) == list(old)  # run.json's key order is the settings' order
    assert EvalConfig.from_json(stored, "run.json") == config
    assert EvalConfig.from_json(old, "run.json").to_json() == config.to_json()

    # The model flags of a replay override the stored options by their flag names.
    command = EvalCommand.build(
        EvalCommand.replay(stored, "run.json", {"model_timeout": 5.0, "out": "o"})
    )
    assert command.run_settings().agent_options.to_json() == {**OLD_OPTIONS, "timeout_s": 5.0}


@pytest.mark.parametrize(
    ("agent", "options", "message"),
    [
        ("expert", {"model": "m"}, "agent 'expert' takes no options, got model"),
        ("frontier", {"model": "m"}, "unknown frontier option 'model'; known: dialog_policy"),
        ("openai-vlm", {"model": "m"}, "the openai-vlm agent needs --base-url"),
        ("openai-vlm", {**OLD_OPTIONS, "max_retries": "-1"}, "max_retries = '-1': Input should"),
        ("openai-vlm", {**OLD_OPTIONS, "device": "cpu"}, "unknown openai-vlm option 'device'"),
        ("vlln", {"model": "m", "max_tokens": "many"}, "vlln option max_tokens = 'many'"),
    ],
)
def test_agent_options_are_checked_against_the_agents_class(
    agent: str, options: dict[str, str], message: str
) -> None:
    with pytest.raises(ConfigError, match=message) as error:
        EvalConfig(agent=agent, task="iign", preset="small", agent_options=options)
    assert "\n" not in str(error.value)
