"""The peer allowlist (KAME_ALLOWED_PEERS): what it allows, and one log line per refused peer."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from kame.net import peers
from kame.net.peers import parse

from ..support import free_port, kame_command, ros_env


def test_addresses_networks_and_host_names() -> None:
    allowlist = parse("10.231.0.2, 192.168.7.0/24 localhost")
    assert allowlist.allows("10.231.0.2")
    assert allowlist.allows("192.168.7.200")
    assert allowlist.allows("::ffff:192.168.7.9")  # an IPv4 peer on an IPv6 socket
    assert not allowlist.allows("10.231.0.3")
    assert not allowlist.allows("192.168.8.1")
    assert not allowlist.allows("not an address")


def test_this_machine_is_always_allowed() -> None:
    allowlist = parse("10.231.0.2")
    assert allowlist.allows("127.0.0.1") and allowlist.allows("127.0.1.1") and allowlist.allows("::1")


@pytest.mark.parametrize(("text", "problem"), [
    ("10.0.0.0/33", "[10.0.0.0/33] is not a network"),
    ("no-such-host.invalid", "[no-such-host.invalid] is neither an address nor a host name that resolves"),
])
def test_a_malformed_list_says_which_entry(text: str, problem: str) -> None:
    with pytest.raises(ValueError, match=problem.replace("[", r"\[").replace("]", r"\]")):
        parse(text)


def test_admit_logs_each_refused_address_once(caplog: pytest.LogCaptureFixture) -> None:
    try:
        peers.configure("10.231.0.2")
        assert peers.admit(("10.231.0.2", 4000), "kame-xmlrpc")
        assert peers.admit(("127.0.0.1", 4000), "kame-xmlrpc")
        for port in (4000, 4001, 4002):
            assert not peers.admit(("10.231.0.3", port), "kame-xmlrpc")
            assert not peers.admit(("10.231.0.3", port), "kame-tcpros")
        refused = [r.getMessage() for r in caplog.records]
        assert refused == [f"refused a connection to the {server} from 10.231.0.3: it is not in "
                           "KAME_ALLOWED_PEERS [10.231.0.2]" for server in ("kame-xmlrpc", "kame-tcpros")]
    finally:
        peers.configure(None)
    assert peers.admit(("10.231.0.3", 4000), "kame-xmlrpc")  # no list: everyone, as ROS 1


def test_a_malformed_list_in_effect_refuses_everyone_but_this_machine(caplog: pytest.LogCaptureFixture) -> None:
    try:
        peers.configure("10.0.0.0/33")
        assert peers.admit(("127.0.0.1", 1), "master")
        assert not peers.admit(("10.0.0.1", 1), "master")
        assert "the allowlist is malformed" in caplog.text
    finally:
        peers.configure(None)



@pytest.mark.parametrize("program", ["kame.cli.rosmaster", "kame.cli.roscore"])
def test_roscore_refuses_a_malformed_allowed_peers_option(program: str, tmp_path: Path) -> None:
    result = subprocess.run(kame_command(program, "-p", str(free_port()), "--allowed-peers", "10.0.0.0/33"),
                            env=ros_env(tmp_path), capture_output=True, text=True, timeout=30)
    assert result.returncode == 2, result
    assert "KAME_ALLOWED_PEERS: [10.0.0.0/33] is not a network" in result.stderr
