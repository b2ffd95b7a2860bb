"""The advertised and bound host: rosgraph.network's rules (get_address_override, get_host_name)."""

from __future__ import annotations

import socket
from pathlib import Path

import pytest

from kame import environ
from kame.net import interfaces
from kame.net.address import address_override, advertised_host, bind_host, host_addresses, local_address, uri_host
from kame.node.config import node_config


def test_override_order_special_then_ros_hostname_then_ros_ip() -> None:
    env = {"ROS_HOSTNAME": "named", "ROS_IP": "10.0.0.9"}
    assert address_override(env, {"hostname": "arg", "ip": "10.1.1.1"}) == "arg"
    assert address_override(env, {"ip": "10.1.1.1"}) == "10.1.1.1"
    assert address_override(env) == "named"
    assert address_override({"ROS_IP": "10.0.0.9"}) == "10.0.0.9"
    assert address_override({}) is None


def test_an_empty_ros_hostname_hides_ros_ip_and_gives_no_override() -> None:
    assert address_override({"ROS_HOSTNAME": "", "ROS_IP": "10.0.0.9"}) is None


def test_advertised_host_without_override_is_the_host_name_unless_loopback(monkeypatch: pytest.MonkeyPatch) -> None:
    assert advertised_host("given") == "given"
    monkeypatch.setattr(socket, "gethostname", lambda: "robot")
    assert advertised_host(None) == "robot"
    monkeypatch.setattr(socket, "gethostname", lambda: "localhost")
    assert advertised_host(None) == local_address()


def test_local_address_prefers_the_only_or_first_non_loopback(monkeypatch: pytest.MonkeyPatch) -> None:
    import kame.net.address as address

    monkeypatch.setattr(address, "local_addresses", lambda ipv6=False: ["127.0.0.1", "192.168.1.5", "10.0.0.1"])
    assert local_address() == "192.168.1.5"
    monkeypatch.setattr(address, "local_addresses", lambda ipv6=False: ["127.0.1.1"])
    assert local_address() == "127.0.1.1"
    monkeypatch.setattr(address, "local_addresses", lambda ipv6=False: ["127.0.0.1", "127.0.1.1"])
    assert local_address() == "127.0.0.1"


def test_bind_host() -> None:
    assert bind_host("localhost") == "127.0.0.1"
    assert bind_host("127.0.0.2") == "127.0.0.2"
    assert bind_host("::1") == "127.0.0.1"
    assert bind_host("robot") == "0.0.0.0"
    assert bind_host(None) == "0.0.0.0"


def test_ros_ipv6_binds_the_ipv6_wildcard_or_loopback() -> None:
    assert host_addresses({"ROS_IPV6": "on", "ROS_HOSTNAME": "robot"}) == ("robot", "::")
    assert host_addresses({"ROS_IPV6": "on", "ROS_IP": "127.0.0.1"}) == ("127.0.0.1", "::1")
    assert host_addresses({"ROS_IPV6": "yes", "ROS_HOSTNAME": "robot"}) == ("robot", "0.0.0.0")  # only 'on' counts


def test_local_address_with_ipv6_falls_back_to_the_ipv6_loopback(monkeypatch: pytest.MonkeyPatch) -> None:
    import kame.net.address as address

    monkeypatch.setattr(address, "local_addresses", lambda ipv6=False: ["::1", "127.0.0.1"] if ipv6 else ["127.0.0.1"])
    assert local_address(ipv6=True) == "::1"


@pytest.mark.parametrize(("env", "warning"), [
    ({"ROS_HOSTNAME": ""}, "invalid ROS_HOSTNAME (an empty string)"),
    ({"ROS_HOSTNAME": "http://robot:11311"}, "invalid ROS_HOSTNAME (protocol and port should not be included)"),
    ({"ROS_HOSTNAME": "http://robot"}, "invalid ROS_HOSTNAME (protocol should not be included)"),
    # Python's urlparse reads 'robot:1234' as the scheme 'robot', so rosgraph says 'protocol' there
    ({"ROS_HOSTNAME": "robot:1234"}, "invalid ROS_HOSTNAME (protocol should not be included)"),
    ({"ROS_HOSTNAME": "10.0.0.1:1234"}, "invalid ROS_HOSTNAME (port should not be included)"),
    ({"ROS_IP": ""}, "invalid ROS_IP (an empty string)"),
    ({"ROS_IP": "http://10.0.0.1"}, "invalid ROS_IP (protocol should not be included)"),
    ({"ROS_IP": "10.0.0.1:80"}, "invalid ROS_IP (port should not be included)"),
    ({"ROS_IP": "robot"}, "invalid ROS_IP (must be a valid IPv4 or IPv6 address)"),
])
def test_malformed_ros_hostname_and_ros_ip_warn_as_rosgraph_and_are_still_used(
        env: dict[str, str], warning: str, capsys: pytest.CaptureFixture[str]) -> None:
    value = next(iter(env.values()))
    assert address_override(env) == (value or None)
    assert capsys.readouterr().err == warning + "\n"


def test_well_formed_values_do_not_warn(capsys: pytest.CaptureFixture[str]) -> None:
    for env in ({"ROS_HOSTNAME": "robot.lab"}, {"ROS_IP": "10.0.0.1"}, {"ROS_IP": "fe80::1"}):
        address_override(env)
    assert capsys.readouterr().err == ""


def test_node_config_from_the_command_line_and_environment() -> None:
    env = {"ROS_NAMESPACE": "ns", "ROS_MASTER_URI": "http://m:1/", "ROS_IP": "127.0.0.3"}
    config = node_config("talker", {}, env, {"chatter": "out"})
    assert (config.name, config.master_uri, config.host, config.bind_host) == (
        "/ns/talker", "http://m:1/", "127.0.0.3", "127.0.0.3")
    assert dict(config.remappings) == {"/ns/chatter": "/ns/out"}
    special = {"name": "other", "ns": "/top", "master": "http://x:2/", "ip": "10.9.9.9"}
    config = node_config("talker", special, env)
    assert (config.name, config.master_uri, config.host, config.bind_host) == (
        "/top/other", "http://x:2/", "10.9.9.9", "0.0.0.0")
    assert environ.master_uri({}) == environ.DEFAULT_MASTER_URI


def test_unreachable_reason_names_what_a_wrong_advertised_address_causes() -> None:
    import errno

    from kame.net.address import DOES_NOT_RESOLVE, unreachable_reason

    def wrapped(cause: BaseException) -> OSError:
        try:
            raise OSError("requestTopic: failed") from cause
        except OSError as exc:
            return exc

    assert unreachable_reason(wrapped(socket.gaierror(-2, "Name or service not known"))) == DOES_NOT_RESOLVE
    assert unreachable_reason(ConnectionRefusedError()) == "the connection was refused"
    assert unreachable_reason(wrapped(TimeoutError())) == "it did not answer"
    assert unreachable_reason(OSError(errno.EHOSTUNREACH, "No route to host")) == "there is no route to it"
    assert unreachable_reason(ValueError("bad header")) is None
    assert unreachable_reason(ConnectionResetError()) is None


def test_ipv6_addresses_are_listed_by_interface_global_first_link_local_with_its_interface(
        monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    """In getifaddrs' order, as rosgraph (netifaces) lists them: /proc/net/if_inet6 is in hash order."""
    table = tmp_path / "if_inet6"
    table.write_text("fe8000000000000000fc00fffe000001 04 40 20 80     eth0\n"
                     "00000000000000000000000000000001 01 80 10 80       lo\n"
                     "fd000000000000000000000000000002 04 40 00 82     eth0\n")
    monkeypatch.setattr(interfaces, "_IF_INET6", str(table))
    monkeypatch.setattr(interfaces, "_ipv4_addresses", lambda: ["127.0.0.1", "192.0.2.2"])
    assert interfaces.local_addresses(ipv6=True) == ["::1", "fd00::2", "fe80::fc:ff:fe00:1%eth0", "127.0.0.1",
                                                     "192.0.2.2"]
    assert local_address(ipv6=True) == "fd00::2"


def test_uri_host_brackets_an_ipv6_address() -> None:
    assert uri_host("::1") == "[::1]" and uri_host("robot") == "robot" and uri_host("10.0.0.1") == "10.0.0.1"
