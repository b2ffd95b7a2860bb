"""Which address a ROS process advertises and binds, from ROS_HOSTNAME / ROS_IP (spec §1.4).

- The advertised host is the override (`__hostname`/`__ip` argument, else ROS_HOSTNAME, else
  ROS_IP), else the machine's host name unless that is `localhost` or `127.*`, in which case an
  address of this machine is used instead.
- A loopback override binds to that loopback address only; anything else binds all interfaces.
"""

from __future__ import annotations

import socket
from collections.abc import Mapping


def address_override(env: Mapping[str, str], special: Mapping[str, str] | None = None) -> str | None:
    """`special` is the parsed `__hostname`/`__ip` arguments (see kame.names.parse_args)."""
    special = special or {}
    return special.get("hostname") or special.get("ip") or env.get("ROS_HOSTNAME") or env.get("ROS_IP") or None


def _is_loopback(host: str) -> bool:
    return host == "localhost" or host.startswith("127.") or host == "::1"


def advertised_host(override: str | None) -> str:
    if override:
        return override
    name = socket.gethostname()
    if name and not _is_loopback(name):
        return name
    try:
        address = socket.gethostbyname(name)
    except OSError:
        return "127.0.0.1"
    return address


def bind_host(override: str | None) -> str:
    if override and _is_loopback(override):
        return "127.0.0.1" if override == "localhost" else override
    return "0.0.0.0"


def is_this_host(address: str) -> bool:
    """Whether `address` (a name or an address) names this machine: its host name, its fully
    qualified name, or an address its host name resolves to."""
    if address in (socket.gethostname(), socket.getfqdn()):
        return True
    try:
        return address in {a[4][0] for a in socket.getaddrinfo(socket.gethostname(), None)}
    except OSError:
        return False
