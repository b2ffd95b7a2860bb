"""Separate hosts for the tests: Linux network namespaces on one private bridge.

`Lan` makes one namespace per host, each with `lo` and an `eth0` (a veth whose other end sits on
a bridge in a namespace of its own), an address in 10.231.0.0/24 and a hosts file naming every
host (`/etc/netns/<ns>/hosts`, which `ip netns exec` binds over /etc/hosts). Namespace names
carry the test run's PID; traffic never leaves the namespaces made here. `close()` deletes every
namespace (and with them the veths and the bridge) and hosts file it made.

It needs root and iproute2: `Lan.unavailable()` says why not, for a skip.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

NETNS_ETC = Path("/etc/netns")
SUBNET = "10.231.0"


@dataclass(frozen=True)
class Host:
    name: str  # what the other hosts call it (their hosts files)
    ns: str  # the network namespace
    address: str

    def command(self, args: Sequence[str]) -> list[str]:
        """`args` run on this host (ip netns exec replaces itself by the program: same PID)."""
        return ["ip", "netns", "exec", self.ns, *args]


def _ip(*args: str) -> None:
    subprocess.run(["ip", *args], check=True, capture_output=True, text=True)


class Lan:
    def __init__(self, names: Sequence[str], tag: str | None = None) -> None:
        self.tag = tag or f"kame{os.getpid()}"
        self.switch = f"{self.tag}sw"
        self.hosts = {name: Host(name, f"{self.tag}{name}", f"{SUBNET}.{i + 1}") for i, name in enumerate(names)}
        self._made: list[str] = []
        try:
            self._build()
        except BaseException:
            self.close()
            raise

    @staticmethod
    def unavailable() -> str | None:
        if os.geteuid() != 0:
            return "network namespaces need root"
        if shutil.which("ip") is None:
            return "iproute2's ip is not installed"
        return None

    def _add_ns(self, ns: str) -> None:
        _ip("netns", "add", ns)
        self._made.append(ns)
        _ip("-n", ns, "link", "set", "lo", "up")

    def _build(self) -> None:
        self._add_ns(self.switch)
        _ip("-n", self.switch, "link", "add", "br0", "type", "bridge")
        _ip("-n", self.switch, "link", "set", "br0", "up")
        hosts_file = "127.0.0.1 localhost\n" + "".join(f"{h.address} {h.name}\n" for h in self.hosts.values())
        for i, host in enumerate(self.hosts.values()):
            self._add_ns(host.ns)
            port = f"p{i}"
            _ip("link", "add", "eth0", "netns", host.ns, "type", "veth", "peer", "name", port, "netns", self.switch)
            _ip("-n", self.switch, "link", "set", port, "master", "br0", "up")
            _ip("-n", host.ns, "addr", "add", f"{host.address}/24", "dev", "eth0")
            _ip("-n", host.ns, "link", "set", "eth0", "up")
            etc = NETNS_ETC / host.ns
            etc.mkdir(parents=True, exist_ok=True)
            (etc / "hosts").write_text(hosts_file)

    def __getitem__(self, name: str) -> Host:
        return self.hosts[name]

    def close(self) -> None:
        for ns in reversed(self._made):
            subprocess.run(["ip", "netns", "del", ns], capture_output=True)
            shutil.rmtree(NETNS_ETC / ns, ignore_errors=True)
        self._made.clear()
        try:
            NETNS_ETC.rmdir()  # only when no other namespace has files there
        except OSError:
            pass
