"""roslaunch.server (the parent's XML-RPC server over a process monitor) and
ROSLaunchConfig.assign_machines: the same answers as Debian's real roslaunch on one request
(tests/libs/launch_server_driver.py run by both interpreters)."""

from __future__ import annotations

import getpass
import socket
import sys
from pathlib import Path
from typing import Any

import pytest

from . import debian

DRIVER = Path(__file__).with_name("launch_server_driver.py")
REQUEST: dict[str, Any] = {
    "calls": [
        ["list_processes", []], ["process_info", ["talker-1"]], ["process_info", ["nope-1"]],
        ["get_node_names", []], ["list_children", []], ["register", ["stranger", "http://unroutable:1324/"]],
        ["register", ["child-1", "http://unroutable:1325/"]], ["list_children", []],
        ["process_died", ["talker-1", 3]], ["log", ["child-1", 2, "started with pid [5]"]],
        ["log", ["child-1", 2, "plain"]], ["log", ["child-1", 8, "broken"]], ["no_such_method", []],
        ["get_pid", [1]], ["_shutdown", ["private"]],
    ],
    "configs": [
        {"machines": [["a", "localhost", None], ["b", "localhost", None], ["c", "127.0.0.1", None],
                      ["far", "10.255.255.1", None], ["pw", "localhost", "secret"]],
         "nodes": [None, "a", "b", "c", "far", "pw"], "test": "b"},
        {"machines": [["a", "localhost", None], ["b", "localhost", None]], "nodes": ["b", "a", None], "test": None},
    ],
    "addresses": [["localhost", None], ["127.0.0.1", None], ["127.0.1.1", None], ["10.255.255.1", None],
                  [socket.gethostname(), None], ["localhost", getpass.getuser()], ["127.0.0.1", "someone_else"],
                  ["10.255.255.1", getpass.getuser()]],
}


def run(python: str) -> dict[str, Any]:
    answer: dict[str, Any] = debian.run(DRIVER, REQUEST, python)
    return answer


def test_parent_server_and_machines_on_kame() -> None:
    ours = run(sys.executable)
    served = ours["served"]
    answers = dict(zip([f"{m} {a}" for m, a in REQUEST["calls"]], served["answers"][1:], strict=True))
    assert served["answers"][0] == [1, True, True] and served["announced"]
    assert answers["list_processes []"] == [1, "processes on parent machine", [[["talker-1", 2], ["rosout-1", 1]], []]]
    assert answers["process_info ['nope-1']"] == [-1, "no process by that name", {}]
    assert answers["register ['stranger', 'http://unroutable:1324/']"][0] == -1
    assert served["answers"][8] == [1, "roslaunch children", ["http://unroutable:1325/"]]
    assert answers["no_such_method []"] == answers["get_pid [1]"] == answers["_shutdown ['private']"] == "Fault"
    assert served["died"] == [["talker-1", 3]]  # heard past the listener that failed
    assert served["logged"] == ["\x1b[1m[child-1]: started with pid [5]\x1b[0m", "[child-1]: plain",
                                "\x1b[31m[child-1]: broken\x1b[0m"]
    # machines alike but for their name are one, the first a node names; "" (nodes without a
    # machine) has no env-loader, unlike those added, so stays apart
    assert ours["assigned"][0] == ["RLException", ["", "a", "a", "c", "far", "pw", "a"], True]
    assert ours["assigned"][1] == ["RLException", ["b", "b", "", ""], False]
    assert served["after"] is None
    assert ours["local"] == [True, True, True, False, True, True, False, False]  # another user: over SSH


@pytest.mark.skipif(not debian.has("roslaunch.server", "roslaunch.config", "rosgraph_msgs.msg"),
                    reason="Debian's roslaunch is not installed")
def test_roslaunch_server_answers_as_debians() -> None:
    assert run(sys.executable) == run(str(debian.SYSTEM_PYTHON))
