"""`rostopic echo` without -n waits on an event, not a poll: Ctrl-C and a shutdown request
(rosnode kill's slave API call) both end it, cleanly, and a shutdown request ends its wait for
a topic nobody publishes yet."""

from __future__ import annotations

import os
import signal
import sys
import time
import xmlrpc.client
from collections.abc import Iterator
from pathlib import Path

import pytest

from kame.node.node import Node, NodeConfig
from kame.node.topics import serialize_frame
from std_msgs.msg import String

from ..support import Proc, free_port, kame_command, ros_env, wait_for_master

BIN = Path(sys.executable).parent


@pytest.fixture(scope="module")
def master(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[str, dict[str, str]]]:
    home = tmp_path_factory.mktemp("echo_stops")
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = ros_env(home, uri)
    proc = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), env)
    try:
        wait_for_master(uri, proc=proc)
        yield uri, env
    finally:
        proc.stop()


def _echo_node(master_uri: str, topic: str) -> str:
    """The name of the rostopic node subscribed to `topic`, once it is."""
    proxy = xmlrpc.client.ServerProxy(master_uri)
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline:
        for name, subscribers in proxy.getSystemState("/test")[2][1]:
            if name == topic and subscribers:
                return str(subscribers[0])
        time.sleep(0.05)
    raise AssertionError(f"nobody subscribed to {topic}")


@pytest.mark.parametrize("how", ["sigint", "shutdown request"])
def test_echo_ends_when_asked(master: tuple[str, dict[str, str]], how: str) -> None:
    uri, env = master
    topic = f"/echo_{how.replace(' ', '_')}"
    node = Node(NodeConfig("/echo_source", uri, "127.0.0.1"))
    echo = Proc([str(BIN / "rostopic"), "echo", topic], env)
    try:
        pub = node.advertise(topic, String._type, String._md5sum, String._full_text, latch=True)
        pub.publish_frame(serialize_frame(String(data="hello")))
        echo.wait_line('data: "hello"', timeout=20)
        if how == "sigint":
            os.kill(echo.pid, signal.SIGINT)
        else:
            name = _echo_node(uri, topic)
            code, _, node_uri = xmlrpc.client.ServerProxy(uri).lookupNode("/test", name)
            assert code == 1
            try:
                xmlrpc.client.ServerProxy(node_uri).shutdown("/test", "asked to stop")
            except OSError as exc:  # seen once beside a second suite: say what the echo did meanwhile
                raise AssertionError(f"{name} at {node_uri} did not answer ({exc}); rostopic echo's exit status "
                                     f"{echo.popen.poll()}, it said:\n{''.join(echo.out)}{''.join(echo.err)}") from exc
        assert echo.popen.wait(20) == 0
    finally:
        out, err = echo.stop()
        node.shutdown("test over")
    assert "Traceback" not in err, err
    assert out.startswith('data: "hello"\n---\n')


def _rostopic_node(master_uri: str) -> str:
    """The name of the (one) rostopic node up, found by its /rosout publication."""
    proxy = xmlrpc.client.ServerProxy(master_uri)
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline:
        for name, publishers in proxy.getSystemState("/test")[2][0]:
            found = [p for p in publishers if p.startswith("/rostopic_")]
            if name == "/rosout" and found:
                return str(found[0])
        time.sleep(0.05)
    raise AssertionError("no rostopic node publishes /rosout")


def test_a_shutdown_request_ends_the_wait_for_a_topic_nobody_publishes(master: tuple[str, dict[str, str]]) -> None:
    uri, env = master
    echo = Proc([str(BIN / "rostopic"), "echo", "/nobody_publishes_this"], env)
    try:
        code, _, node_uri = xmlrpc.client.ServerProxy(uri).lookupNode("/test", _rostopic_node(uri))
        assert code == 1
        xmlrpc.client.ServerProxy(node_uri).shutdown("/test", "asked to stop")
        assert echo.popen.wait(20) == 0
    finally:
        _, err = echo.stop()
    assert "Traceback" not in err, err
    assert "WARNING: topic [/nobody_publishes_this] does not appear to be published yet" in err
