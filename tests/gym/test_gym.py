"""The Gymnasium environments: registration, spaces, the checker, vector determinism."""

from __future__ import annotations

import itertools
import os
import signal
import subprocess
import sys
import threading
from pathlib import Path
from typing import Any

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import vlln.gym
from tests.stairs import SCENE_ID, upstairs_episode
from vlln.errors import ConfigError
from vlln.gym.remote import RemoteEnv
from vlln.gym.spaces import TALK
from vlln.sim.agent import Action
from vlln.tasks.split_files import load_or_build_split

SMALL = {"houses": 1, "preset": "small", "width": 64, "height": 48}


@pytest.fixture(scope="module")
def cache_dir(split_cache: Path) -> str:
    """The test split's first house (the session's, tests/conftest.py)."""
    return str(split_cache)


@pytest.mark.slow
def test_registration_happens_only_in_vlln_gym() -> None:
    code = (
        "import gymnasium, vlln, vlln.eval.runner, vlln.cli;"
        "print(any(k.startswith('vlln/') for k in gymnasium.registry))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
    gymnasium.register_envs(vlln.gym)
    assert set(vlln.gym.ENV_IDS) <= set(gymnasium.registry)


@pytest.mark.slow
def test_module_prefixed_id_needs_no_import(cache_dir: str) -> None:
    code = (
        "import gymnasium;"
        f"env = gymnasium.make('vlln.gym:vlln/IIGN-v0', cache_dir={cache_dir!r}, houses=1,"
        " preset='small', width=32, height=24);"
        "obs, info = env.reset(seed=1); print(obs['instruction']); env.close()"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.startswith("Search for the ")


@pytest.mark.slow
@pytest.mark.parametrize("env_id", sorted(vlln.gym.ENV_IDS))
def test_check_env_passes(env_id: str, cache_dir: str) -> None:
    env = gymnasium.make(env_id, cache_dir=cache_dir, max_steps=20, **SMALL)
    check_env(env.unwrapped, skip_render_check=True)
    obs, _ = env.reset(seed=3)
    assert env.observation_space.contains(obs)
    env.close()


def test_question_is_answered_and_budget_counts_down(cache_dir: str) -> None:
    env = gymnasium.make("vlln/IIGN-v0", cache_dir=cache_dir, dialog_budget=2, **SMALL)
    obs, _ = env.reset(seed=0)
    assert obs["questions_left"] == 2
    obs, *_ = env.step({"action": TALK, "question": "What color is it?"})
    assert obs["oracle_answer"] and obs["questions_left"] == 1
    obs, *_ = env.step({"action": int(Action.TURN_LEFT), "question": ""})
    assert obs["oracle_answer"] == ""
    env.close()


def test_options_choose_episode_file_and_index(cache_dir: str, tmp_path: Path) -> None:
    from vlln.tasks.episode import write_episodes

    episodes = load_or_build_split("test", "ign", 1, cache_dir, progress=False)
    path = tmp_path / "two.json.gz"
    write_episodes(path, episodes[3:5])
    env = gymnasium.make("vlln/IGN-v0", cache_dir=cache_dir, **SMALL)
    _, info = env.reset(options={"episode_file": str(path), "episode_index": 1})
    assert info["episode_id"] == episodes[4].episode_id
    env.close()


def _rollout(env: Any, seeds: list[int], steps: int) -> list[Any]:
    obs, _ = env.reset(seed=seeds)
    frames = [obs["rgb"].copy(), obs["gps"].copy()]
    for step in range(steps):
        index = [Action.TURN_LEFT, Action.MOVE_FORWARD, Action.TURN_RIGHT][step % 3]
        actions = {"action": np.full(len(seeds), int(index)), "question": ("",) * len(seeds)}
        obs, reward, *_ = env.step(actions)
        frames += [obs["rgb"].copy(), obs["gps"].copy(), np.asarray(reward)]
    return frames


@pytest.mark.slow
def test_async_vector_rollout_equals_sequential(cache_dir: str) -> None:
    kwargs = dict(cache_dir=cache_dir, max_steps=50, **SMALL)
    vector = gymnasium.make_vec(
        "vlln/IIGN-v0",
        num_envs=2,
        vectorization_mode="async",
        vector_kwargs={"context": "spawn"},
        **kwargs,
    )
    sync = gymnasium.make_vec("vlln/IIGN-v0", num_envs=2, vectorization_mode="sync", **kwargs)
    try:
        parallel = _rollout(vector, [5, 9], 6)
        sequential = _rollout(sync, [5, 9], 6)
    finally:
        vector.close()
        sync.close()
    assert len(parallel) == len(sequential)
    for a, b in zip(parallel, sequential, strict=True):
        np.testing.assert_array_equal(a, b)


@pytest.mark.slow
def test_height_rises_as_the_expert_climbs_to_a_target_upstairs(
    cache_dir: str, tmp_path: Path
) -> None:
    from vlln.tasks.episode import write_episodes
    from vlln.tasks.scenes import SceneCache

    scenes = SceneCache(capacity=1)
    episode = upstairs_episode(scenes.get(SCENE_ID), "stairs-gym")
    scenes.close()
    path = tmp_path / "upstairs.json.gz"
    write_episodes(path, [episode])
    env = gymnasium.make(
        "vlln/IGN-v0", episode_file=str(path), privileged=True, width=64, height=48
    )
    obs, _ = env.reset(seed=0)
    heights = [float(obs["height"][0])]
    for _ in range(200):
        obs, _, terminated, truncated, _ = env.step(int(obs["expert_action"]))
        heights.append(float(obs["height"][0]))
        assert env.observation_space.contains(obs)  # structure ids are negative
        if terminated or truncated:
            break
    env.close()
    assert heights[0] == 0.0 and heights[-1] == pytest.approx(2.8)
    assert all(b >= a for a, b in itertools.pairwise(heights)), "it only climbs"


_GUARD_S = 300  # a hang fails the test after this, it never blocks the suite
PACKAGE_ROOT = str(Path(vlln.gym.__file__).resolve().parents[2])


def _run_guarded(args: list[str], cwd: Path, env: dict[str, str] | None = None) -> str:
    """Run ``args`` in a session of its own; kill the whole session (forked workers too) if
    it hangs. Returns its standard output and fails on a non-zero exit."""
    env = dict(os.environ if env is None else env)  # the vlln under test, from any folder
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [PACKAGE_ROOT, env.get("PYTHONPATH")]))
    process = subprocess.Popen(
        args,
        cwd=cwd,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        out, err = process.communicate(timeout=_GUARD_S)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        process.communicate()
        pytest.fail(f"{args[-1]} hung for {_GUARD_S} s")
    assert process.returncode == 0, err
    return out


_STEP_THEN_VECTOR = """
import sys
import gymnasium, numpy as np, vlln.gym
kwargs = dict(cache_dir=sys.argv[1], max_steps=50, houses=1, preset="small", width=64, height=48)
env = gymnasium.make("vlln/IIGN-v0", **kwargs)
env.reset(seed=0)
env.step({"action": 2, "question": ""})  # this process has rendered now
vector = gymnasium.make_vec("vlln/IIGN-v0", num_envs=2, vectorization_mode="async", **kwargs)
sync = gymnasium.make_vec("vlln/IIGN-v0", num_envs=2, vectorization_mode="sync", **kwargs)
actions = {"action": np.array([2, 1]), "question": ("", "")}
pairs = [(vector.reset(seed=[5, 9])[0], sync.reset(seed=[5, 9])[0])]
pairs.append((vector.step(actions)[0], sync.step(actions)[0]))
same = all(np.array_equal(a[k], b[k]) for a, b in pairs for k in ("rgb", "depth", "gps"))
vector.close(), sync.close(), env.close()
print("same" if same else "different")
"""


@pytest.mark.slow
def test_async_vector_env_after_an_env_has_stepped_in_the_process(
    cache_dir: str, tmp_path: Path
) -> None:
    # The workers are forked (the default start method) after this process rendered.
    script = tmp_path / "step_then_vector.py"
    script.write_text(_STEP_THEN_VECTOR)
    out = _run_guarded([sys.executable, str(script), cache_dir], tmp_path)
    assert out.strip() == "same"


@pytest.mark.slow
def test_the_docs_snippet_runs_as_pasted(tmp_path: Path) -> None:
    text = (Path(__file__).parents[2] / "docs" / "gym.md").read_text(encoding="utf-8")
    snippet = text.split("```python\n", 1)[1].split("```", 1)[0]
    script = tmp_path / "snippet.py"
    script.write_text(snippet)
    # An empty cache: the snippet builds the first mp3d test house's episodes, as a user's would.
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path / "cache")}
    out = _run_guarded([sys.executable, str(script)], tmp_path, env)
    assert out.splitlines()[-1] == "(2, 480, 640, 3)"


@pytest.mark.slow
def test_arguments_that_do_not_pickle_are_refused_in_one_line() -> None:
    # What a process that cannot render sends to the environment's own process.
    with pytest.raises(ConfigError, match="cannot be sent to the environment's own process"):
        RemoteEnv({"oracle": threading.Lock()})


def test_the_benchmarks_houses_unless_told() -> None:
    """By default the episodes are those vlln eval scores on (mp3d houses); a preset that does
    not exist is one line that names the presets."""
    assert gymnasium.make("vlln/IIGN-v0").unwrapped.preset == "mp3d"
    assert gymnasium.make("vlln/IIGN-v0", preset="small").unwrapped.preset == "small"
    with pytest.raises(ConfigError, match="unknown house preset 'big'"):
        gymnasium.make("vlln/IIGN-v0", preset="big")
