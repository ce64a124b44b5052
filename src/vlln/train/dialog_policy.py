"""``vlln train dialog-policy``: learn when the frontier agent asks, by PPO on training houses.

The environment is :class:`vlln.gym.dialog.DialogEnv` (whole navigation episodes, paused at
each decision point); the reward is success − λ per question. stable-baselines3's PPO trains
a small MLP on one CPU thread; the folder then holds the whole model (``model.zip``), the
actor's weights for play (``actor.npz``) and the card (:mod:`vlln.agents.frontier.learned`).
Every random choice comes from ``--seed``: the network, the episode order, agents and oracles.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import Field

from vlln.agents.frontier.asking import ACTION_NAMES, FEATURES
from vlln.agents.frontier.learned import (
    CARD_FILE,
    MODEL_FILE,
    WEIGHTS_FILE,
    Layer,
    PolicyCard,
    save_policy,
)
from vlln.config import Config
from vlln.extras import require_extra
from vlln.files import replace_folder
from vlln.tasks.spec import DEFAULT_MAX_STEPS

RL_PACKAGES = ("gymnasium", "torch", "stable_baselines3")


class DialogPolicyConfig(Config):
    """Settings of ``vlln train dialog-policy``."""

    out: Path
    """policy folder (replaced on a rerun)"""
    lam: float = Field(0.05, ge=0)
    """price of one question: the reward is success - lam x questions"""
    timesteps: Annotated[int, Field(ge=1)] = 20_000
    """decisions to train on"""
    seed: int = 0
    """seed of the network, the episode order, the agent and the oracle"""
    split: Literal["train", "val"] = "train"
    """houses to train on (never the test houses)"""
    houses: Annotated[int, Field(ge=1)] | None = None
    """houses of the split (none: all 61 train houses)"""
    preset: str = "small"
    """house preset: small (fast to play) or mp3d (the benchmark's, about 4x slower)"""
    detector: str = "noisy"
    """the frontier agent's detector: noisy or truth"""
    budget: Annotated[int, Field(ge=1)] = 5
    """dialog budget of the training episodes"""
    explore_every: Annotated[int, Field(ge=1)] = 20
    """exploration steps without a candidate between two exploration decision points"""
    max_steps: Annotated[int, Field(ge=1)] = DEFAULT_MAX_STEPS
    """counted-step cap of the training episodes (vlln eval's default)"""
    n_steps: Annotated[int, Field(ge=8)] = 256
    """decisions per PPO update"""
    minutes: Annotated[float, Field(gt=0)] | None = None
    """stop training after this many minutes (the update under way is dropped; none: no
    limit)"""
    warm_start: bool = True
    """start from the fixed triggers: before PPO, the actor is fitted (on drawn beliefs, no
    episodes) to ask each point's own kind 70 % of the time (--no-warm-start: from scratch)"""
    cache_dir: Path | None = None
    """where built splits are kept (none: ~/.cache/vlln)"""


def _owned(entry: Path) -> bool:
    return entry.name in (CARD_FILE, WEIGHTS_FILE, MODEL_FILE, "train_log.jsonl")


def train_dialog_policy(config: DialogPolicyConfig, log: Any = print) -> PolicyCard:
    """Train, write the folder and return its card; ``log`` gets a line per PPO update."""
    require_extra("rl", "vlln train dialog-policy", RL_PACKAGES)
    return replace_folder(config.out, lambda folder: _train(config, folder, log), _owned)


def _train(config: DialogPolicyConfig, folder: Path, log: Any) -> PolicyCard:
    import torch
    from stable_baselines3 import PPO

    from vlln.gym.dialog import DialogEnv, training_episodes

    torch.set_num_threads(1)
    episodes = training_episodes(config.split, config.houses, config.preset, config.cache_dir)
    env = DialogEnv(
        episodes,
        lam=config.lam,
        seed=config.seed,
        detector=config.detector,
        budget=config.budget,
        explore_every=config.explore_every,
        max_steps=config.max_steps,
    )
    started = time.monotonic()
    model = PPO(
        "MlpPolicy",
        env,
        n_steps=config.n_steps,
        batch_size=min(64, config.n_steps),
        gamma=1.0,  # the reward is the episode's: no discount over its decisions
        gae_lambda=0.95,
        ent_coef=0.01,
        policy_kwargs={"net_arch": {"pi": [32, 32], "vf": [32, 32]}},
        seed=config.seed,
        device="cpu",
    )
    if config.warm_start:
        imitate_fixed_triggers(model, config.seed)
    try:
        deadline = None if config.minutes is None else started + 60.0 * config.minutes
        model.learn(config.timesteps, callback=_progress(folder, started, deadline, log))
    finally:
        env.close()
    model.save(folder / MODEL_FILE)
    card = PolicyCard(
        features=list(FEATURES),
        actions=list(ACTION_NAMES),
        explore_every=config.explore_every,
        lam=config.lam,
        seed=config.seed,
        timesteps=int(model.num_timesteps),
        episodes=env.played,
        seconds=round(time.monotonic() - started, 1),
        split=config.split,
        preset=config.preset,
        houses=len({episode.scene_id for episode in episodes}),
        detector=config.detector,
        budget=config.budget,
    )
    save_policy(folder, card, actor_layers(model))
    return card


def imitate_fixed_triggers(model: Any, seed: int, share: float = 0.7) -> None:
    """Fit the actor to the fixed triggers, softened: at each point its own kind (colour at the
    start, the way while exploring, "is this the one?" at a candidate) with probability
    ``share``, the other actions sharing the rest. PPO then starts from the hand-set rule
    and explores around it, instead of from a policy that asks at random."""
    import torch

    rng = np.random.default_rng(seed)
    count = 2048
    beliefs = rng.random((count, len(FEATURES))).astype(np.float32)
    points = rng.integers(0, 3, count)
    first = FEATURES.index("at_start")
    beliefs[:, first : first + 3] = np.eye(3, dtype=np.float32)[points]
    own = np.array([ACTION_NAMES.index(k) for k in ("attribute", "route", "disambiguation")])
    target = np.full((count, len(ACTION_NAMES)), (1.0 - share) / (len(ACTION_NAMES) - 1))
    target[np.arange(count), own[points]] = share
    policy = model.policy
    params = [*policy.mlp_extractor.policy_net.parameters(), *policy.action_net.parameters()]
    optimizer = torch.optim.Adam(params, lr=3e-3)
    x = torch.as_tensor(beliefs)
    y = torch.as_tensor(target, dtype=torch.float32)
    for _ in range(300):
        logits = policy.action_net(policy.mlp_extractor.forward_actor(x))
        loss = -(y * torch.log_softmax(logits, dim=1)).sum(dim=1).mean()
        optimizer.zero_grad()
        loss.backward()
        optimizer.step()


def actor_layers(model: Any) -> list[Layer]:
    """The actor's layers of an MlpPolicy (tanh hidden layers, then the action head)."""
    linear = [m for m in model.policy.mlp_extractor.policy_net if hasattr(m, "weight")]
    layers = [*linear, model.policy.action_net]
    return [
        (
            layer.weight.detach().numpy().astype(np.float32),
            layer.bias.detach().numpy().astype(np.float32),
        )
        for layer in layers
    ]


def _progress(folder: Path, started: float, deadline: float | None, log: Any) -> Any:
    """A callback that logs each update's episodes (SR, questions; train_log.jsonl) and ends
    training once ``deadline`` is past."""
    import json

    from stable_baselines3.common.callbacks import BaseCallback

    from vlln.tasks.metrics import success

    class Progress(BaseCallback):
        def __init__(self) -> None:
            super().__init__()
            self.ended: list[tuple[bool, int]] = []

        def _on_step(self) -> bool:
            for info in self.locals["infos"]:
                record = info.get("record")
                if record is not None:
                    self.ended.append((success(record), len(record.dialog)))
            return not self.past_deadline  # a partial rollout is dropped

        @property
        def past_deadline(self) -> bool:
            return deadline is not None and time.monotonic() > deadline

        def _on_rollout_end(self) -> None:
            if not self.ended:
                return
            line = {
                "timesteps": self.num_timesteps,
                "seconds": round(time.monotonic() - started, 1),
                "episodes": len(self.ended),
                "sr": round(100.0 * float(np.mean([s for s, _ in self.ended])), 1),
                "questions": round(float(np.mean([q for _, q in self.ended])), 2),
            }
            with (folder / "train_log.jsonl").open("a") as handle:
                handle.write(json.dumps(line) + "\n")
            log(" ".join(f"{key}={value}" for key, value in line.items()))
            self.ended = []

    return Progress()
