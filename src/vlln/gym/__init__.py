"""Gymnasium environments for the three tasks.

Importing this module registers ``vlln/IIGN-v0``, ``vlln/IGN-v0`` and ``vlln/ObjectNav-v0``;
nothing else in the package registers anything. Gymnasium 1.x's convention::

    import gymnasium, vlln.gym
    gymnasium.register_envs(vlln.gym)
    env = gymnasium.make("vlln/IIGN-v0", houses=1)

or, with no import at all, ``gymnasium.make("vlln.gym:vlln/IIGN-v0")``. The datasheet is in
:mod:`vlln.gym.env`.
"""

from __future__ import annotations

import gymnasium

from vlln.gym.env import VllnEnv

ENV_IDS = {"vlln/IIGN-v0": "iign", "vlln/IGN-v0": "ign", "vlln/ObjectNav-v0": "objectnav"}

for _env_id, _task in ENV_IDS.items():
    if _env_id not in gymnasium.registry:
        gymnasium.register(_env_id, entry_point="vlln.gym.env:VllnEnv", kwargs={"task": _task})

__all__ = ["ENV_IDS", "VllnEnv"]
