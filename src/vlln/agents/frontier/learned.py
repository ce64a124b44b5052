"""A dialog policy learned by ``vlln train dialog-policy``, read from its folder.

The folder holds ``dialog_policy.json`` (the card: the features and actions it was trained
on, λ, seed, houses, timesteps), ``actor.npz`` (the policy network's weights, the only part
play needs) and ``model.zip`` (the whole stable-baselines3 model, for people and for more
training). Play runs the small network in numpy, so evaluation needs neither torch nor
stable-baselines3, and the policy copies cheaply when an episode's budgets share prefixes.
The card is written and read here only.
"""

from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path
from typing import Annotated

import numpy as np
from numpy.typing import NDArray
from pydantic import Field

from vlln.agents.frontier.asking import ACTION_NAMES, FEATURES, Decision
from vlln.config import Config
from vlln.errors import ConfigError, DataFormatError
from vlln.files import ReadCap, parse_json, write_text_atomic

CARD_FILE = "dialog_policy.json"
WEIGHTS_FILE = "actor.npz"
MODEL_FILE = "model.zip"
_CARD_CAP = ReadCap("a dialog-policy card", 1)

Layer = tuple[NDArray[np.float32], NDArray[np.float32]]  # (weights out × in, bias)


class PolicyCard(Config):
    """What a learned dialog policy reads and how it was trained."""

    features: list[str]
    """the belief features it reads, in order"""
    actions: list[str]
    """its actions, in order: walk on, then the question kinds"""
    explore_every: Annotated[int, Field(ge=1)]
    """exploration steps without a candidate between two exploration decision points"""
    lam: float
    """the reward's price of one question (reward: success - lam x questions)"""
    seed: int
    """seed of training: the network's weights, episode order, agent and oracle"""
    timesteps: Annotated[int, Field(ge=0)]
    """decisions trained on"""
    episodes: Annotated[int, Field(ge=0)] = 0
    """navigation episodes played in training"""
    seconds: Annotated[float, Field(ge=0)] = 0.0
    """wall-clock training time"""
    split: str
    """the split its episodes came from (train: never the test houses)"""
    preset: str
    """the house preset of its episodes"""
    houses: Annotated[int, Field(ge=1)]
    """houses of the split it trained on"""
    detector: str
    """the frontier agent's detector in training"""
    budget: Annotated[int, Field(ge=0)]
    """the dialog budget of its training episodes"""


class LearnedPolicy:
    """The trained network's most likely action at each decision point (deterministic)."""

    def __init__(self, card: PolicyCard, layers: list[Layer]) -> None:
        self.card = card
        self._layers = layers

    @property
    def explore_every(self) -> int:
        return self.card.explore_every

    def scores(self, features: NDArray[np.float32]) -> NDArray[np.float32]:
        """The network's action scores (logits): tanh hidden layers, a linear head."""
        x = features
        for weights, bias in self._layers[:-1]:
            x = np.tanh(weights @ x + bias)
        weights, bias = self._layers[-1]
        out: NDArray[np.float32] = weights @ x + bias
        return out

    def choose(self, decision: Decision) -> str | None:
        return decision.action(int(np.argmax(self.scores(decision.features()))))


def save_policy(folder: Path, card: PolicyCard, layers: list[Layer]) -> None:
    """Write the card and the weights into ``folder`` (the model zip is the trainer's)."""
    arrays: dict[str, NDArray[np.float32]] = {}
    for k, (weights, bias) in enumerate(layers):
        arrays[f"w{k}"] = np.asarray(weights, np.float32)
        arrays[f"b{k}"] = np.asarray(bias, np.float32)
    with (folder / WEIGHTS_FILE).open("wb") as handle:
        np.savez(handle, **arrays)  # type: ignore[arg-type]
    write_text_atomic(folder / CARD_FILE, json.dumps(card.to_json(), indent=2) + "\n")


@lru_cache(maxsize=8)
def load_policy(folder: str) -> LearnedPolicy:
    """The policy in ``folder``; a missing folder or file, or one that does not fit this
    agent's features and actions, is one :class:`ConfigError` line."""
    path = Path(folder)
    hint = "make one with: vlln train dialog-policy --out FOLDER"
    if not (path / CARD_FILE).is_file() or not (path / WEIGHTS_FILE).is_file():
        raise ConfigError(f"{path} is not a dialog-policy folder (no {CARD_FILE}); {hint}")
    try:
        card = PolicyCard.from_json(parse_json(_CARD_CAP.read(path / CARD_FILE)), str(path))
        with np.load(path / WEIGHTS_FILE, allow_pickle=False) as stored:
            count = len(stored.files) // 2
            layers = [(stored[f"w{k}"], stored[f"b{k}"]) for k in range(count)]
    except (OSError, ValueError, KeyError, DataFormatError) as error:
        raise ConfigError(f"{path}: unreadable dialog policy ({error}); {hint}") from None
    if card.features != list(FEATURES) or card.actions != list(ACTION_NAMES):
        raise ConfigError(f"{path}: trained on other features or actions than this agent's")
    _check_shapes(path, layers)
    return LearnedPolicy(card, layers)


def _check_shapes(path: Path, layers: list[Layer]) -> None:
    width = len(FEATURES)
    for weights, bias in layers:
        if weights.ndim != 2 or weights.shape[1] != width or bias.shape != (weights.shape[0],):
            raise ConfigError(f"{path}: {WEIGHTS_FILE} holds layers of mismatched sizes")
        width = weights.shape[0]
    if not layers or width != len(ACTION_NAMES):
        raise ConfigError(f"{path}: {WEIGHTS_FILE} does not end in {len(ACTION_NAMES)} actions")
