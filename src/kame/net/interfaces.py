"""This machine's network addresses and host name resolution, for checks such as roswtf's.

- Local addresses are the IPv4 address of every interface (SIOCGIFADDR), and with
  `ipv6` first the IPv6 ones of /proc/net/if_inet6; where those are not available (not Linux),
  what the machine's own host name resolves to.
- `resolve` gives a name's addresses (IPv4 only unless `ipv6`), or None when it does not resolve.
- UnknownHostError is what a connection to a name that does not resolve fails with, so tools
  can say "unknown host" without importing socket.
"""

from __future__ import annotations

import socket
import struct

UnknownHostError = socket.gaierror

_SIOCGIFADDR = 0x8915
_IF_INET6 = "/proc/net/if_inet6"
_LINK_SCOPE = 0x20
# /proc/net/if_inet6's scope column (global 0, site 0x40, link 0x20, host 0x10) in the order the
# kernel keeps an interface's addresses: global first
_SCOPE_RANK = {0x00: 0, 0x40: 1, 0x20: 2, 0x10: 3}


def _ipv4_addresses() -> list[str]:
    import fcntl

    found = []
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sock:
        for _, name in socket.if_nameindex():
            request = struct.pack("256s", name.encode()[:15])
            try:
                answer = fcntl.ioctl(sock.fileno(), _SIOCGIFADDR, request)
            except OSError:
                continue  # no IPv4 address on this interface
            found.append(socket.inet_ntoa(answer[20:24]))
    return found


def _ipv6_addresses() -> list[str]:
    """As getifaddrs lists them (rosgraph's netifaces): by interface, the widest scope first,
    link-local ones with their interface (`fe80::1%eth0`, the form a socket can use)."""
    try:
        with open(_IF_INET6, encoding="ascii") as f:
            rows = [line.split() for line in f]
    except OSError:
        return []
    found = []
    for row in sorted((row for row in rows if len(row) == 6),
                      key=lambda row: (int(row[1], 16), _SCOPE_RANK.get(int(row[3], 16), 0))):
        address = socket.inet_ntop(socket.AF_INET6, bytes.fromhex(row[0]))
        found.append(f"{address}%{row[5]}" if int(row[3], 16) == _LINK_SCOPE else address)
    return found


def local_addresses(ipv6: bool = False) -> list[str]:
    try:
        v4 = _ipv4_addresses()
    except (ImportError, OSError, AttributeError):
        return resolve(socket.gethostname(), ipv6) or []
    return [*_ipv6_addresses(), *v4] if ipv6 else v4


def resolve(host: str, ipv6: bool = True) -> list[str] | None:
    family = socket.AF_UNSPEC if ipv6 else socket.AF_INET
    try:
        infos = socket.getaddrinfo(host, 0, family, 0, socket.SOL_TCP)
    except (OSError, UnicodeError):
        return None
    return list(dict.fromkeys(str(info[4][0]) for info in infos))


def hostname() -> str:
    return socket.gethostname()
