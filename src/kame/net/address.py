"""Which address a ROS process advertises and binds: rosgraph.network's rules, once for all of kame.

- The override (get_address_override) is the `__hostname:=` or `__ip:=` argument, else
  ROS_HOSTNAME when it is set, else ROS_IP when it is set. A variable set to the empty string
  counts as set (ROS_IP is then not looked at) and gives no override, as in rosgraph.
- The advertised host (get_host_name) is the override, else the machine's host name unless
  that is `localhost` or `127.*`, in which case an address of this machine is used instead
  (get_local_address: the only one, else the first that is not loopback, else 127.0.0.1).
- A loopback override binds to that loopback address only; anything else binds all interfaces.
- ROS_IPV6=on (use_ipv6) adds this machine's IPv6 addresses and binds `::1` / `::` instead.
- A malformed ROS_HOSTNAME or ROS_IP (empty, with a protocol or a port, not an address) is
  still used, with rosgraph's warning on stderr and in the log.
"""

from __future__ import annotations

import errno
import logging
import socket
import sys
from collections.abc import Mapping
from typing import NamedTuple

from kame.net.interfaces import local_addresses, resolve

log = logging.getLogger("kame.net.address")


def use_ipv6(env: Mapping[str, str]) -> bool:
    return env.get("ROS_IPV6") == "on"


def address_override(env: Mapping[str, str], special: Mapping[str, str] | None = None) -> str | None:
    """`special` is the parsed `__hostname`/`__ip` arguments (see kame.names.parse_args)."""
    special = special or {}
    for value in (special.get("hostname"), special.get("ip")):
        if value:
            return value
    return environment_override(env) or None


def environment_override(env: Mapping[str, str]) -> str | None:
    """ROS_HOSTNAME when it is set, else ROS_IP when it is set, else None; a variable set to ''
    gives '' (rosgraph's get_address_override answers it). A malformed value is warned about."""
    for variable in ("ROS_HOSTNAME", "ROS_IP"):
        if variable in env:
            problem = override_problem(variable, env[variable])
            if problem:
                sys.stderr.write(problem + "\n")
                log.warning(problem)
            return env[variable]
    return None


def override_problem(variable: str, value: str) -> str | None:
    """rosgraph's warning for a malformed ROS_HOSTNAME or ROS_IP, or None when it looks right."""
    if value == "":
        return f"invalid {variable} (an empty string)"
    if variable == "ROS_HOSTNAME":
        if ":" not in value:  # no scheme and no port: most names, read without urllib.parse (0.46 MB)
            return None
        from urllib.parse import urlparse

        if urlparse(value).scheme:
            has_port = bool(_port(value))
            return f"invalid ROS_HOSTNAME (protocol {'and port ' if has_port else ''}should not be included)"
        return "invalid ROS_HOSTNAME (port should not be included)"
    if "://" in value:
        return "invalid ROS_IP (protocol should not be included)"
    if "." in value and value.rfind(":") > value.rfind("."):
        return "invalid ROS_IP (port should not be included)"
    if "." not in value and ":" not in value:
        return "invalid ROS_IP (must be a valid IPv4 or IPv6 address)"
    return None


def _port(url: str) -> int | None:
    from urllib.parse import urlparse

    try:
        return urlparse(url).port
    except ValueError:
        return None


def _is_loopback(host: str) -> bool:
    return host == "localhost" or host.startswith("127.") or host == "::1"


def local_address(ipv6: bool = False) -> str:
    addresses = local_addresses(ipv6)
    if len(addresses) == 1:
        return addresses[0]
    for address in addresses:
        if not _is_loopback(address):
            return address
    return "::1" if ipv6 else "127.0.0.1"


def advertised_host(override: str | None, ipv6: bool = False) -> str:
    if override:
        return override
    name = socket.gethostname()
    if name and not _is_loopback(name):
        return name
    return local_address(ipv6)


def bind_host(override: str | None, ipv6: bool = False) -> str:
    if override and _is_loopback(override):
        if ipv6:
            return "::1"
        return override if override.startswith("127.") else "127.0.0.1"
    return "::" if ipv6 else "0.0.0.0"


def uri_host(host: str) -> str:
    """`host` as it stands in a URI: an IPv6 address in brackets."""
    return f"[{host}]" if ":" in host else host


def is_local_address(host: str, ipv6: bool = False) -> bool:
    """rosgraph's is_local_address: whether `host` resolves (to IPv4 only unless `ipv6`) to a
    loopback address or one of this machine's; a name that does not resolve is not local."""
    found = resolve(host, ipv6)
    if found is None:
        return False
    local = {"localhost", *local_addresses(ipv6)}
    return any(_is_loopback(ip) for ip in found) or bool(set(found) & local)


class HostAddresses(NamedTuple):
    advertised: str  # the host in this process's URIs
    bind: str  # where its servers listen


def host_addresses(env: Mapping[str, str], special: Mapping[str, str] | None = None) -> HostAddresses:
    """The advertised and bound host of a process with this environment and special arguments:
    what the master, every node, roslaunch and the tools use."""
    override = address_override(env, special)
    ipv6 = use_ipv6(env)
    return HostAddresses(advertised_host(override, ipv6), bind_host(override, ipv6))


def resolvable(host: str) -> str | bytes:
    """`host` as getaddrinfo takes it without the idna codec: bytes when it is ASCII. A str
    always goes through the codec, whose module loads stringprep and unicodedata (half a
    megabyte) at every node's first connection."""
    return host.encode("ascii") if host.isascii() else host


def is_this_host(address: str) -> bool:
    """Whether `address` (a name or an address) names this machine: its host name, its fully
    qualified name, or an address its host name resolves to."""
    if address in (socket.gethostname(), socket.getfqdn()):
        return True
    try:
        return address in {a[4][0] for a in socket.getaddrinfo(socket.gethostname(), None)}
    except OSError:
        return False


DOES_NOT_RESOLVE = "its name does not resolve on this machine"
NO_ROUTE = "there is no route to it"
REFUSED = "the connection was refused"
_UNREACHABLE_ERRNOS = {errno.EHOSTUNREACH, errno.ENETUNREACH, errno.EHOSTDOWN, errno.ENETDOWN}


def unreachable_reason(exc: BaseException) -> str | None:
    """What about reaching an address went wrong, for the errors that a wrong advertised address
    causes (its name does not resolve, nothing answers, no route, refused); None for the rest."""
    seen: BaseException | None = exc
    while seen is not None:
        if isinstance(seen, socket.gaierror):
            return DOES_NOT_RESOLVE
        if isinstance(seen, ConnectionRefusedError):
            return REFUSED
        if isinstance(seen, (TimeoutError, socket.timeout)):
            return "it did not answer"
        if isinstance(seen, OSError) and seen.errno in _UNREACHABLE_ERRNOS:
            return NO_ROUTE
        seen = seen.__cause__ or seen.__context__
    return None
