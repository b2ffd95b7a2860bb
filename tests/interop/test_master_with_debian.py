"""kame's rosmaster with Debian's real ROS 1: a rospy node and the ros* command-line tools.

One kame master and one real rospy node (ros_peer_node.py) per module; each tool runs with
/usr/bin/python3 against the master, as a user would type it.
"""

from __future__ import annotations

import re
import time
import xmlrpc.client
from collections.abc import Iterator
from pathlib import Path

import pytest
import yaml

from ..support import SYSTEM_PYTHON, Proc, free_port, have_debian_ros, kame_command, ros_env, ros_tool, wait_for_master

pytestmark = pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 (rosmaster, rospy) is not installed")

PEER = Path(__file__).with_name("ros_peer_node.py")


class Graph:
    def __init__(self, home: Path) -> None:
        self.port = free_port()
        self.uri = f"http://127.0.0.1:{self.port}/"
        self.env = ros_env(home, self.uri)
        self.master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(self.port)), self.env)
        self.peer: Proc | None = None

    def tool(self, name: str, *args: str, check: bool = True) -> str:
        result = ros_tool(name, *args, env=self.env, check=check)
        return result.stdout

    def proxy(self) -> xmlrpc.client.ServerProxy:
        return xmlrpc.client.ServerProxy(self.uri)

    def stop(self) -> None:
        if self.peer is not None:
            self.peer.stop()
        self.master.stop()


@pytest.fixture(scope="module")
def graph(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Graph]:
    g = Graph(tmp_path_factory.mktemp("ros_home"))
    try:
        wait_for_master(g.uri, proc=g.master)
        g.peer = Proc([SYSTEM_PYTHON, str(PEER)], g.env)
        g.peer.wait_line("ready")
        yield g
    finally:
        g.stop()


def test_rostopic_echo_receives_from_rospy_talker(graph: Graph) -> None:
    out = graph.tool("rostopic", "echo", "-n", "3", "/chatter")
    assert re.findall(r'data: "hello \d+"', out).__len__() == 3
    assert out.count("---") == 3


def test_rostopic_list_info_type(graph: Graph) -> None:
    out = graph.tool("rostopic", "list", "-v")
    assert " * /chatter [std_msgs/String] 1 publisher" in out
    assert " * /rosout [rosgraph_msgs/Log] 1 publisher" in out
    assert "/chatter" in graph.tool("rostopic", "list")
    info = graph.tool("rostopic", "info", "/chatter")
    assert "Type: std_msgs/String" in info and " * /peer (http://127.0.0.1:" in info
    assert graph.tool("rostopic", "type", "/chatter").strip() == "std_msgs/String"


def test_rosnode_list_info_ping(graph: Graph) -> None:
    assert "/peer" in graph.tool("rosnode", "list").split()
    info = graph.tool("rosnode", "info", "/peer")
    assert "Node [/peer]" in info and " * /chatter [std_msgs/String]" in info and " * /set_flag" in info
    assert "Pid: " in info
    ping = graph.tool("rosnode", "ping", "-c", "2", "/peer")
    assert ping.count("reply from http://127.0.0.1:") == 2


def test_rosservice_list_and_call(graph: Graph) -> None:
    services = graph.tool("rosservice", "list").split()
    assert "/set_flag" in services and "/peer/get_loggers" in services
    assert graph.tool("rosservice", "type", "/set_flag").strip() == "std_srvs/SetBool"
    out = graph.tool("rosservice", "call", "/set_flag", "true")
    assert yaml.safe_load(out) == {"success": True, "message": "flag True"}


def test_rosparam_round_trips(graph: Graph, tmp_path: Path) -> None:
    graph.tool("rosparam", "set", "/rp/int", "5")
    graph.tool("rosparam", "set", "/rp/dict", "{a: 1, b: {c: hello, d: [1, 2.5, true]}}")
    assert graph.tool("rosparam", "get", "/rp/int").strip() == "5"
    want = {"a": 1, "b": {"c": "hello", "d": [1, 2.5, True]}}
    assert yaml.safe_load(graph.tool("rosparam", "get", "/rp/dict")) == want
    listed = graph.tool("rosparam", "list").split()
    assert {"/rp/int", "/rp/dict/a", "/rp/dict/b/c", "/rp/dict/b/d"} <= set(listed)
    everything = yaml.safe_load(graph.tool("rosparam", "get", "/"))
    assert everything["rp"]["dict"]["b"]["c"] == "hello"
    dump = tmp_path / "dump.yaml"
    graph.tool("rosparam", "dump", str(dump), "/rp")
    assert yaml.safe_load(dump.read_text())["dict"]["a"] == 1
    graph.tool("rosparam", "load", str(dump), "/copy")
    assert yaml.safe_load(graph.tool("rosparam", "get", "/copy/dict/b")) == {"c": "hello", "d": [1, 2.5, True]}
    graph.tool("rosparam", "delete", "/copy")
    result = ros_tool("rosparam", "get", "/copy", env=graph.env, check=False)
    assert result.returncode == 1 and "Parameter [/copy] is not set" in result.stderr


def test_get_param_cached_follows_the_master(graph: Graph) -> None:
    assert graph.peer is not None
    graph.peer.wait_line("cached None")
    graph.tool("rosparam", "set", "/cached", "41")
    graph.peer.wait_line("cached 41")
    graph.proxy().setParam("/someone", "/cached", "changed")
    graph.peer.wait_line("cached 'changed'")


def test_peer_is_told_to_shut_down_when_its_name_is_taken(tmp_path: Path) -> None:
    g = Graph(tmp_path)
    try:
        wait_for_master(g.uri, proc=g.master)
        first = Proc([SYSTEM_PYTHON, str(PEER)], g.env)
        try:
            first.wait_line("ready")
            g.peer = Proc([SYSTEM_PYTHON, str(PEER)], g.env)
            g.peer.wait_line("ready")
            deadline = time.monotonic() + 10
            while first.popen.poll() is None and time.monotonic() < deadline:
                time.sleep(0.05)
            assert first.popen.poll() is not None, "the first /peer did not exit"
            assert "new node registered with same name" in "".join(first.out + first.err)
        finally:
            first.stop()
    finally:
        g.stop()
