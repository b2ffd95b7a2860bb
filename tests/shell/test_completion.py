"""Tab completion of the ros* tools: the candidate tables (kame.shell.complete) with a fake
graph, and bash itself calling the registered completion function (COMP_WORDS/COMP_CWORD in,
COMPREPLY out) against a live kame master."""

from __future__ import annotations

import sys
import xmlrpc.client
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from kame.shell.complete import Sources, candidates
from tests.shell.shell_env import bash, clean_env, complete
from tests.support import Proc, free_port, wait_for_master

BIN = Path(sys.executable).parent


class FakeGraph(Sources):
    def system_state(self) -> tuple[list[Any], list[Any], list[Any]]:
        return ([["/chatter", ["/talker"]], ["/turtle1/pose", ["/turtlesim"]]],
                [["/chatter", ["/listener"]]],
                [["/spawn", ["/turtlesim"]], ["/clear", ["/turtlesim"]]])

    def params(self) -> list[str]:
        return ["/background_b", "/background_g", "/run_id"]

    def topic_type(self, topic: str) -> str | None:
        return "std_msgs/String" if topic == "/chatter" else None


@pytest.mark.parametrize(("line", "expected"), [
    ("rostopic ", ["bw", "delay", "echo", "find", "hz", "info", "list", "pub", "type"]),
    ("rostopic e", ["echo"]),
    ("rostopic echo ", ["/chatter", "/turtle1/pose"]),
    ("rostopic echo -n 1 /t", ["/turtle1/pose"]),
    ("rostopic pub /chatter ", ["std_msgs/String"]),
    ("rostopic hz /chatter /", ["/chatter", "/turtle1/pose"]),
    ("rosnode ", ["cleanup", "info", "kill", "list", "machine", "ping"]),
    ("rosnode info /t", ["/talker", "/turtlesim"]),
    ("rosservice call /", ["/clear", "/spawn"]),
    ("rosparam get /background_", ["/background_b", "/background_g"]),
    ("rosparam ", ["delete", "dump", "get", "list", "load", "set"]),
    ("rosmsg show std_msgs/Str", ["std_msgs/String"]),
    ("rossrv show turtlesim/Sp", ["turtlesim/Spawn"]),
    ("rosrun rospy_tut", ["rospy_tutorials"]),
    ("rosrun rospy_tutorials ", ["add_two_ints_client", "add_two_ints_server", "listener", "listener.py",
                                 "listener_header", "listener_subscribe_notify", "listener_with_user_data",
                                 "on_shutdown", "param_talker", "talker", "talker.py", "talker_header"]),
    ("rosrun turtlesim ", ["draw_square", "mimic", "turtle_teleop_key", "turtlesim_node"]),
    ("roscd rospy_tut", ["rospy_tutorials/"]),
    ("roscd rospy_tutorials/s", ["rospy_tutorials/scripts/", "rospy_tutorials/srv/"]),
    ("roscat rospy_tutorials Add", ["AddTwoInts.srv"]),
    ("rospack find turtles", ["turtlesim"]),
    ("rosclean ", ["check", "purge"]),
    ("catkin_create_pkg my_pkg std_m", ["std_msgs"]),
    ("rostopic echo --no", ["--nostr", "--noarr"]),
])
def test_candidates(line: str, expected: list[str]) -> None:
    words = line.split(" ")
    assert candidates(words, len(words) - 1, FakeGraph({"ROS_PACKAGE_PATH": ""})) == expected


def test_no_master_gives_no_names_quickly() -> None:
    src = Sources({"ROS_MASTER_URI": f"http://127.0.0.1:{free_port()}/", "ROS_PACKAGE_PATH": ""})
    assert candidates(["rostopic", "echo", ""], 2, src) == []
    assert candidates(["rosparam", "get", ""], 2, src) == []


@pytest.fixture(scope="module")
def master(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    home = tmp_path_factory.mktemp("master")
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    proc = Proc([str(BIN / "rosmaster"), "--core", "-p", str(port)], clean_env(home, uri))
    try:
        wait_for_master(uri, proc=proc)
        m = xmlrpc.client.ServerProxy(uri)
        fake = "http://127.0.0.1:9/"
        m.registerPublisher("/talker", "/chatter", "std_msgs/String", fake)
        m.registerSubscriber("/listener", "/chatter", "std_msgs/String", fake)
        m.registerService("/adder", "/add_two_ints", "rosrpc://127.0.0.1:9", fake)
        m.setParam("/test", "/background_r", 150)
        yield uri
    finally:
        proc.stop()


@pytest.mark.parametrize(("words", "expected"), [
    (("rostopic", ""), ["bw", "delay", "echo", "find", "hz", "info", "list", "pub", "type"]),
    (("rostopic", "echo", "/ch"), ["/chatter"]),
    (("rostopic", "pub", "/chatter", ""), ["std_msgs/String"]),
    (("rosnode", "info", "/"), ["/adder", "/listener", "/talker"]),
    (("rosservice", "call", "/a"), ["/add_two_ints"]),
    (("rosparam", "get", "/back"), ["/background_r"]),
    (("roscd", "rospy_tutorials/sc"), ["rospy_tutorials/scripts/"]),
    (("rosrun", "rospy_tutorials", "t"), ["talker", "talker.py", "talker_header"]),
    (("rosmsg", "show", "geometry_msgs/Twist"), ["geometry_msgs/Twist", "geometry_msgs/TwistStamped",
                                                 "geometry_msgs/TwistWithCovariance",
                                                 "geometry_msgs/TwistWithCovarianceStamped"]),
])
def test_bash_calls_the_completion_function(master: str, tmp_path: Path, words: tuple[str, ...],
                                            expected: list[str]) -> None:
    assert complete(clean_env(tmp_path, master), *words) == expected


def test_every_tool_has_completion(tmp_path: Path) -> None:
    tools = ["rostopic", "rosnode", "rosservice", "rosparam", "rosmsg", "rossrv", "rospack", "rosrun", "roscd",
             "rosls", "rosed", "roscp", "roscat", "rosclean", "rosversion", "roslaunch", "rosbag", "catkin_make",
             "catkin", "catkin_create_pkg", "roscore"]
    result = bash(" ".join(f"complete -p {t};" for t in tools), clean_env(tmp_path))
    assert result.returncode == 0, result.stderr
    assert len(result.stdout.splitlines()) == len(tools)
