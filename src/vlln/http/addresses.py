"""Which hosts are this machine only, and which ports can be listened on."""

from __future__ import annotations

import ipaddress

from vlln.errors import ConfigError


def is_loopback(host: str) -> bool:
    """Whether ``host`` names this machine only: ``localhost`` or a loopback address
    (127.0.0.0/8, ``::1``, also written ``[::1]`` as in URLs)."""
    if host.lower() == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False


def check_port(port: int) -> None:
    """Raise :class:`ConfigError` unless a server can listen on ``port`` (0 picks a free one);
    the value may come from a configuration file, so its type is checked too."""
    if isinstance(port, bool) or not isinstance(port, int) or not 0 <= port <= 65535:
        raise ConfigError(f"port must be a whole number in 0..65535, got {port!r}")
