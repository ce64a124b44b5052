"""``vlln train dialog-policy`` end to end: a short PPO run on a training house, its folder,
and ``vlln eval --agent frontier --dialog-policy P`` playing with it."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from stable_baselines3 import PPO

from vlln.agents.frontier.learned import load_policy
from vlln.cli import main


@pytest.mark.slow
def test_train_a_policy_then_evaluate_with_it(
    tmp_path: Path, split_cache: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    policy = tmp_path / "policy"
    train = ["train", "dialog-policy", "--out", str(policy), "--timesteps", "16", "--n-steps"]
    train += ["8", "--houses", "1", "--cache-dir", str(tmp_path / "cache"), "--lam", "0.1"]
    train += ["--max-steps", "60"]
    assert main(train) == 0
    assert "use it with: vlln eval --agent frontier --dialog-policy" in capsys.readouterr().out
    card = json.loads((policy / "dialog_policy.json").read_text())
    assert card["lam"] == 0.1 and card["split"] == "train" and card["timesteps"] >= 16
    # Play runs the actor in numpy: the same choices as stable-baselines3's own.
    beliefs = np.random.default_rng(0).random((64, len(card["features"]))).astype(np.float32)
    chosen, _ = PPO.load(policy / "model.zip", device="cpu").predict(beliefs, deterministic=True)
    learned = load_policy(str(policy))
    assert list(chosen) == [int(np.argmax(learned.scores(b))) for b in beliefs]

    run = tmp_path / "run"
    evaluate = ["eval", "--agent", "frontier", "--task", "iign", "--houses", "1", "--episodes"]
    evaluate += ["2", "--preset", "small", "--cache-dir", str(split_cache), "--quiet"]
    evaluate += ["--dialog-policy", str(policy), "--max-steps", "60", "--out", str(run)]
    assert main(evaluate) == 0
    stored = json.loads((run / "run.json").read_text())
    assert stored["agent_options"] == {"dialog_policy": str(policy.resolve())}
    assert len((run / "episodes.jsonl").read_text().splitlines()) == 2


def test_a_missing_policy_is_one_line_before_any_work(
    tmp_path: Path, split_cache: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    evaluate = ["eval", "--agent", "frontier", "--task", "iign", "--houses", "1", "--episodes"]
    evaluate += ["2", "--preset", "small", "--cache-dir", str(split_cache), "--quiet"]
    evaluate += ["--dialog-policy", str(tmp_path / "nowhere"), "--out", str(tmp_path / "run")]
    assert main(evaluate) == 2
    error = capsys.readouterr().err
    assert error.startswith("error: ") and error.count("\n") == 1
    assert "not a dialog-policy folder" in error and not (tmp_path / "run").exists()


@pytest.mark.slow
def test_without_stable_baselines3_training_is_one_line(tmp_path: Path) -> None:
    from tests.test_extras import RUN_WITHOUT

    out = tmp_path / "policy"
    command = ["train", "dialog-policy", "--out", str(out)]
    done = subprocess.run(
        [sys.executable, "-c", RUN_WITHOUT, "stable_baselines3", *command],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 2 and done.stderr.count("\n") == 1
    assert "vlln train dialog-policy needs stable_baselines3" in done.stderr
    assert "install the rl extra with" in done.stderr and not out.exists()
