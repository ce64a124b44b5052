"""The completion cache's keys and entries, and the usage ledger's totals."""

from __future__ import annotations

import math
import threading
from pathlib import Path

import pytest

from vlln.oracle.llm.accounting import Pricing, UsageLedger
from vlln.oracle.llm.cache import ResponseCache, cache_key
from vlln.oracle.llm.protocol import Message, Usage

MESSAGES = [Message("user", "Is it red?")]
PARAMS = {"max_tokens": 16, "temperature": 0.0}


def test_every_part_of_a_request_changes_the_key() -> None:
    base = cache_key("https://a/v1", "m", MESSAGES, PARAMS)
    assert base == cache_key("https://a/v1", "m", [Message("user", "Is it red?")], dict(PARAMS))
    variants = [
        cache_key("https://b/v1", "m", MESSAGES, PARAMS),
        cache_key("https://a/v1", "m2", MESSAGES, PARAMS),
        cache_key("https://a/v1", "m", [Message("system", "Is it red?")], PARAMS),
        cache_key("https://a/v1", "m", MESSAGES, {**PARAMS, "temperature": 0.5}),
    ]
    assert len({base, *variants}) == 5


def test_entries_round_trip_and_unreadable_ones_are_misses(tmp_path: Path) -> None:
    cache = ResponseCache(tmp_path)
    key = cache_key("https://a/v1", "m", MESSAGES, PARAMS)
    assert cache.get(key) is None
    cache.put(key, "Yes, it is red. ✓")
    assert ResponseCache(tmp_path).get(key) == "Yes, it is red. ✓"
    (entry,) = tmp_path.rglob("*.json")
    entry.write_text("{truncated", encoding="utf-8")
    assert cache.get(key) is None
    cache.put(key, "again")
    assert cache.get(key) == "again"


@pytest.mark.parametrize(
    "entry",
    [
        b'{"text": ' + b"[" * 100_000 + b"]" * 100_000 + b"}",
        b'{"text": ' + b"9" * 5000 + b"}",
        b'{"text": "' + b" " * (9 << 20) + b'"}',  # past the cap on an entry
    ],
)
def test_a_hostile_entry_is_a_miss(tmp_path: Path, entry: bytes) -> None:
    cache = ResponseCache(tmp_path)
    key = cache_key("https://a/v1", "m", MESSAGES, PARAMS)
    cache.put(key, "first")
    (path,) = tmp_path.rglob("*.json")
    path.write_bytes(entry)
    assert cache.get(key) is None


def test_the_ledger_totals_requests_tokens_and_cost_across_threads() -> None:
    ledger = UsageLedger()
    pricing = Pricing(prompt_per_1k=1.0, completion_per_1k=3.0)
    usage = Usage(prompt_tokens=10, completion_tokens=2)

    def work() -> None:
        for _ in range(250):
            ledger.record(usage, pricing.cost(usage))
            ledger.record_cached()

    threads = [threading.Thread(target=work) for _ in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    ledger.record_failure()
    assert (ledger.requests, ledger.cached_requests, ledger.failed_requests) == (1000, 1000, 1)
    assert (ledger.prompt_tokens, ledger.completion_tokens, ledger.total_tokens) == (
        10_000,
        2_000,
        12_000,
    )
    assert math.isclose(ledger.cost, 1000 * (10 * 1.0 + 2 * 3.0) / 1000.0)
