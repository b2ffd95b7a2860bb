"""Which address a ROS process advertises and binds: rosgraph.network's rules, once for all of kame.

- The override (get_address_override) is the `__hostname:=` or `__ip:=` argument, else
  ROS_HOSTNAME when it is set, else ROS_IP when it is set. A variable set to the empty string
  counts as set (ROS_IP is then not looked at) and gives no override, as in rosgraph.
- The advertised host (get_host_name) is the override, else the machine's host name unless
  that is `localhost` or `127.*`, in which case an address of this machine is used instead
  (get_local_address: the only one, else the first that is not loopback, else 127.0.0.1).
- A loopback override binds to that loopback address only; anything else binds all interfaces.
"""

from __future__ import annotations

import socket
from collections.abc import Mapping

from kame.net.interfaces import local_addresses


def address_override(env: Mapping[str, str], special: Mapping[str, str] | None = None) -> str | None:
    """`special` is the parsed `__hostname`/`__ip` arguments (see kame.names.parse_args)."""
    special = special or {}
    for value in (special.get("hostname"), special.get("ip")):
        if value:
            return value
    for variable in ("ROS_HOSTNAME", "ROS_IP"):
        if variable in env:
            return env[variable] or None
    return None


def _is_loopback(host: str) -> bool:
    return host == "localhost" or host.startswith("127.") or host == "::1"


def local_address() -> str:
    addresses = local_addresses()
    if len(addresses) == 1:
        return addresses[0]
    for address in addresses:
        if not _is_loopback(address):
            return address
    return "127.0.0.1"


def advertised_host(override: str | None) -> str:
    if override:
        return override
    name = socket.gethostname()
    if name and not _is_loopback(name):
        return name
    return local_address()


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
