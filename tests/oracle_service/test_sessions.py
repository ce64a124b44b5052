"""The session store and the service settings, without HTTP."""

from __future__ import annotations

from itertools import count
from typing import Any

import pytest

from vlln.errors import ConfigError
from vlln.oracle.rule_oracle import RuleOracle
from vlln.oracle_service.config import ServiceConfig
from vlln.oracle_service.sessions import ServiceError, Session, SessionStore
from vlln.world.model import ObjectInstance

from .conftest import World


def _session(store: SessionStore, target: ObjectInstance) -> Session:
    return Session(store.fresh_id(), "vlln/house_00076", None, target, (), None, 5, RuleOracle())


def test_store_drops_the_least_recently_used(world: World) -> None:
    ids = count()
    store = SessionStore(2, new_id=lambda: f"s{next(ids)}")
    target = world.sim.house.instance(world.target_id)
    a, b = _session(store, target), _session(store, target)
    store.add(a)
    store.add(b)
    store.get(a.session_id)
    c = _session(store, target)
    store.add(c)
    assert len(store) == 2
    with pytest.raises(ServiceError) as dropped:
        store.get(b.session_id)
    assert dropped.value.status == 404
    store.remove(a.session_id)
    with pytest.raises(ServiceError):
        store.remove(a.session_id)
    assert store.get(c.session_id) is c


def test_fresh_ids_skip_ids_in_use(world: World) -> None:
    issued = iter(["same", "same", "other"])
    store = SessionStore(4, new_id=lambda: next(issued))
    target = world.sim.house.instance(world.target_id)
    store.add(_session(store, target))
    assert store.fresh_id() == "other"


def test_random_session_ids_are_distinct_and_url_safe() -> None:
    store = SessionStore(1)
    ids = {store.fresh_id() for _ in range(100)}
    assert len(ids) == 100
    assert all(len(i) >= 20 and i.replace("-", "").replace("_", "").isalnum() for i in ids)


@pytest.mark.parametrize(
    "settings",
    [
        {"max_sessions": 0},
        {"scene_capacity": 0},
        {"max_body_bytes": -1},
        {"oracle_seed": -1},
        {"token": ""},
        {"token": " padded "},
        {"floor_tolerance": float("nan")},
    ],
)
def test_invalid_settings_are_config_errors(settings: dict[str, Any]) -> None:
    with pytest.raises(ConfigError, match=f"^{next(iter(settings))}: "):
        ServiceConfig.build(settings, flags=False)


def test_duplicate_episode_ids_are_refused(world: World) -> None:
    with pytest.raises(ConfigError, match="twice"):
        ServiceConfig.build({"episodes": (world.episode, world.episode)})
    with pytest.raises(ConfigError):
        SessionStore(0)
