"""The frontier agent's pluggable dialog policy: the default is the fixed triggers, played
exactly as before; a policy's choices and beliefs; a learned policy's folder is checked."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import numpy as np
import pytest

from vlln.agents.frontier import FrontierAgent
from vlln.agents.frontier.asking import (
    ACTION_NAMES,
    FEATURES,
    Belief,
    Decision,
    FixedTriggers,
    Point,
)
from vlln.agents.frontier.learned import PolicyCard, load_policy, save_policy
from vlln.agents.registry import agent_options, make_agent
from vlln.errors import ConfigError
from vlln.oracle.rule_oracle import RuleOracle
from vlln.sim.agent import Action
from vlln.tasks.env import NavigationEnv
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import Talk, TaskConfig, TaskType
from vlln.tasks.split_files import load_or_build_split

# The actions of the frontier agent (seed 11, noisy detector) in the first IIGN episode of the
# small test house at budget 5 (rule oracle, seed 7), played before the dialog policy was
# pluggable: it asks the colour and the way twice.
FIXED_TRIGGERS_RUN = ("bf53a2198788913d", 136)


def play(agent: FrontierAgent, cache: Path) -> list[str]:
    episode = load_or_build_split("test", "iign", 1, cache, progress=False)[0]
    config = TaskConfig(task=TaskType.IIGN, dialog_budget=5)
    env = NavigationEnv([episode], config, SceneCache(), RuleOracle(7), privileged=True)
    observation, _ = env.reset(options={"episode_index": 0})
    agent.reset(env.episode_info())
    actions = []
    while True:
        action = agent.act(observation)
        assert isinstance(action, Talk | Action)
        actions.append(action.text if isinstance(action, Talk) else action.name)
        observation, _, terminated, truncated, _ = env.step(action)
        if terminated or truncated:
            return actions


def digest(actions: list[str]) -> tuple[str, int]:
    return hashlib.sha256("|".join(actions).encode()).hexdigest()[:16], len(actions)


class Recording(FixedTriggers):
    """The fixed triggers, keeping every decision they were asked."""

    def __init__(self, route_after: int) -> None:
        super().__init__(route_after)
        self.decisions: list[Decision] = []

    def choose(self, decision: Decision) -> str | None:
        self.decisions.append(decision)
        return super().choose(decision)


class Silent(Recording):
    def choose(self, decision: Decision) -> str | None:
        super().choose(decision)
        return None


@pytest.mark.slow
def test_the_default_policy_plays_the_fixed_triggers_run(split_cache: Path) -> None:
    agent = make_agent("frontier", 11, "noisy")
    assert isinstance(agent, FrontierAgent) and isinstance(agent.dialog_policy, FixedTriggers)
    assert digest(play(agent, split_cache)) == FIXED_TRIGGERS_RUN


@pytest.mark.slow
def test_a_policy_that_walks_on_never_asks_and_sees_its_beliefs(split_cache: Path) -> None:
    silent = Silent(60)
    actions = play(FrontierAgent(11, detector="noisy", dialog_policy=silent), split_cache)
    assert not any(action.endswith("?") for action in actions)
    points = [d.point for d in silent.decisions]
    assert points[0] == Point.START and points.count(Point.START) == 1
    assert Point.EXPLORE in points
    for decision in silent.decisions:
        features = decision.features()
        assert features.shape == (len(FEATURES),) and features.min() >= 0 and features.max() <= 1
        assert features[FEATURES.index("at_" + decision.point.value)] == 1.0
        assert features[FEATURES.index("budget_left")] == 1.0  # nothing asked


def test_a_kind_not_allowed_at_a_point_walks_on() -> None:
    belief = Belief(1.0, 0.1, False, True, 0, 0, None, 0, False, 20, 30.0, False, 1, False)
    decision = Decision(Point.EXPLORE, ("route",), belief)
    assert decision.features()[FEATURES.index("fitting_distance")] == 1.0  # none seen
    assert [decision.action(k) for k in range(4)] == [None, None, "route", None]


def write_policy(folder: Path, features: list[str] | None = None) -> None:
    card = PolicyCard(
        features=features or list(FEATURES),
        actions=list(ACTION_NAMES),
        explore_every=20,
        lam=0.05,
        seed=0,
        timesteps=0,
        split="train",
        preset="small",
        houses=1,
        detector="noisy",
        budget=5,
    )
    rng = np.random.default_rng(0)
    layers = [
        (rng.normal(size=(8, len(FEATURES))).astype(np.float32), np.zeros(8, np.float32)),
        (rng.normal(size=(4, 8)).astype(np.float32), np.zeros(4, np.float32)),
    ]
    save_policy(folder, card, layers)


def test_a_learned_policy_folder_loads_and_chooses_an_allowed_kind(tmp_path: Path) -> None:
    write_policy(tmp_path)
    policy = load_policy(str(tmp_path))
    assert policy.explore_every == 20
    options = agent_options("frontier", {"dialog_policy": str(tmp_path)})
    assert options.to_json() == {"dialog_policy": str(tmp_path.resolve())}
    assert agent_options("frontier", {}).to_json() == {}


def test_a_missing_or_foreign_policy_folder_is_one_line(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match="not a dialog-policy folder") as missing:
        agent_options("frontier", {"dialog_policy": str(tmp_path / "none")})
    assert "\n" not in str(missing.value) and "vlln train dialog-policy" in str(missing.value)
    write_policy(tmp_path, features=["budget_left"])
    with pytest.raises(ConfigError, match="other features"):
        load_policy(str(tmp_path))
    (tmp_path / "dialog_policy.json").write_text(json.dumps({"features": 3}))
    with pytest.raises(ConfigError, match="unreadable dialog policy"):
        load_policy(str(tmp_path))
