"""Loopback hosts and listening ports, shared by both servers and the OpenAI-compatible client."""

from __future__ import annotations

import pytest

from vlln.errors import ConfigError
from vlln.http.addresses import check_port, is_loopback


@pytest.mark.parametrize(
    "host", ["127.0.0.1", "127.8.9.10", "::1", "[::1]", "localhost", "LocalHost"]
)
def test_loopback_hosts(host: str) -> None:
    assert is_loopback(host)


@pytest.mark.parametrize("host", ["0.0.0.0", "::", "10.0.0.1", "example.org", "localhost.example"])
def test_hosts_beyond_this_machine(host: str) -> None:
    assert not is_loopback(host)


@pytest.mark.parametrize("port", [-1, 65536, True, "8765", 80.0])
def test_ports_that_cannot_be_listened_on(port: object) -> None:
    with pytest.raises(ConfigError, match=r"0\.\.65535"):
        check_port(port)  # type: ignore[arg-type]


def test_ports_that_can() -> None:
    for port in (0, 1, 8765, 65535):
        check_port(port)
