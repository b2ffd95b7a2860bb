"""Who may connect (opt-in, beyond ROS 1): an allowlist of peer addresses and networks.

ROS 1 serves anyone who can reach its ports: the master, every node's XML-RPC server and its
TCPROS server accept any connection, and any peer can publish, set parameters or shut a node
down. KAME_ALLOWED_PEERS (or `roscore --allowed-peers`) names who may: addresses, networks
(`10.0.0.0/24`) and host names (resolved once, when first needed), separated by commas or
spaces. This machine (loopback and its own interfaces' addresses) is always allowed. Every
accept point asks `admit` first: a peer outside the list gets its connection closed and one
log line per address and server. Unset or empty, everyone is served, as in ROS 1.

A malformed list refuses every outside peer (and logs why once): a guard that was asked for
must not open up because of a typo. `parse` checks a list up front (roscore's option does).
"""

from __future__ import annotations

import logging
import os
import re
import threading
from typing import TYPE_CHECKING, Any

from kame.net.interfaces import local_addresses, resolve

ENV = "KAME_ALLOWED_PEERS"

log = logging.getLogger("kame.net.peers")

if TYPE_CHECKING:
    import ipaddress  # imported where used: 0.3 MB that a node without an allowlist never needs

    Network = ipaddress.IPv4Network | ipaddress.IPv6Network


class PeerAllowlist:
    def __init__(self, networks: list[Network], text: str) -> None:
        self.networks = networks
        self.text = text
        # a link-local address is listed with its interface (fe80::1%eth0); allows() compares without
        self._local = {a.split("%", 1)[0] for a in local_addresses(ipv6=True)}

    def allows(self, address: str) -> bool:
        import ipaddress

        try:
            ip = ipaddress.ip_address(address.split("%", 1)[0])
        except ValueError:
            return False
        if isinstance(ip, ipaddress.IPv6Address) and ip.ipv4_mapped is not None:
            ip = ip.ipv4_mapped
        if ip.is_loopback or str(ip) in self._local:
            return True
        return any(ip in network for network in self.networks)


def parse(text: str) -> PeerAllowlist:
    """The allowlist a KAME_ALLOWED_PEERS value names; ValueError saying which entry is wrong."""
    import ipaddress

    networks: list[Network] = []
    for entry in (e for e in re.split(r"[,\s]+", text) if e):
        try:
            networks.append(ipaddress.ip_network(entry, strict=False))
            continue
        except ValueError:
            pass
        if "/" in entry:
            raise ValueError(f"{ENV}: [{entry}] is not a network (expected e.g. 10.0.0.0/24)")
        addresses = resolve(entry)
        if not addresses:
            raise ValueError(f"{ENV}: [{entry}] is neither an address nor a host name that resolves")
        networks.extend(ipaddress.ip_network(a.split("%", 1)[0]) for a in addresses)
    return PeerAllowlist(networks, text)


class _Guard:
    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._loaded = False
        self._allowlist: PeerAllowlist | None = None
        self._broken: str | None = None  # why the configured list could not be read
        self._refused: set[tuple[str, str]] = set()  # (where, address) already logged

    def configure(self, text: str | None) -> None:
        """Use `text` (None or empty: no allowlist) instead of the environment's."""
        with self._lock:
            self._load(text)

    def _load(self, text: str | None) -> None:
        self._loaded, self._allowlist, self._broken, self._refused = True, None, None, set()
        if text and text.strip():
            try:
                self._allowlist = parse(text)
            except ValueError as exc:
                self._broken = str(exc)
                self._allowlist = PeerAllowlist([], "")  # this machine only

    def admit(self, peer: Any, where: str) -> bool:
        with self._lock:
            if not self._loaded:
                self._load(os.environ.get(ENV))
            allowlist, broken = self._allowlist, self._broken
        if allowlist is None:
            return True
        address = str(peer[0]) if isinstance(peer, tuple) and peer else str(peer)
        if allowlist.allows(address):
            return True
        with self._lock:
            first = (where, address) not in self._refused
            self._refused.add((where, address))
        if first:
            why = f"the allowlist is malformed ({broken})" if broken else f"it is not in {ENV} [{allowlist.text}]"
            log.warning("refused a connection to the %s from %s: %s", where, address, why)
        return False


def setup(option: str | None) -> None:
    """For roscore and rosmaster: the `--allowed-peers` option, else the environment's list,
    checked now (ValueError) and passed on to the processes they start through the environment."""
    text = os.environ.get(ENV) if option is None else option
    if text and text.strip():
        parse(text)
    if option is not None:
        os.environ[ENV] = option
    _GUARD.configure(text)


_GUARD = _Guard()
configure = _GUARD.configure
admit = _GUARD.admit
