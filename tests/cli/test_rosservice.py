"""rosservice end to end: kame's installed command against a live kame graph (roscore and a kame
rospy node serving turtlesim/Spawn, AddTwoInts, Empty, SetBool and a failing Trigger), then side
by side with Debian's real rosservice on the same graph (ports masked)."""

from __future__ import annotations

import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.cli.live_graph import LiveGraph, live_graph, mask, no_master_env
from tests.support import have_debian_ros

SERVICES = ["/add_two_ints", "/clear", "/fail", "/graph_node/get_loggers", "/graph_node/set_logger_level",
            "/set_flag", "/spawn"]


@pytest.fixture(scope="module")
def graph(tmp_path_factory: pytest.TempPathFactory) -> Iterator[LiveGraph]:
    with live_graph(tmp_path_factory.mktemp("rosservice")) as g:
        yield g


def ok(graph: LiveGraph, *args: str, input: str | None = None) -> str:
    result = graph.kame("rosservice", *args, input=input)
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""
    return result.stdout


def fails(graph: LiveGraph, *args: str, status: int = 2) -> str:
    result = graph.kame("rosservice", *args)
    assert result.returncode == status, result.stdout + result.stderr
    assert result.stdout == "" and "Traceback" not in result.stderr
    return result.stderr


def test_list(graph: LiveGraph) -> None:
    listed = ok(graph, "list").splitlines()
    assert [s for s in listed if not s.startswith("/rosout")] == SERVICES
    assert ok(graph, "list", "/graph_node") == "/graph_node/get_loggers\n/graph_node/set_logger_level\n"
    assert "/spawn /graph_node\n" in ok(graph, "list", "-n")


def test_type_info_uri_args_find(graph: LiveGraph) -> None:
    assert ok(graph, "type", "/spawn") == "turtlesim/Spawn\n"
    assert mask(ok(graph, "info", "/spawn")) == (
        "Node: /graph_node\nURI: rosrpc://<host>:<port>\nType: turtlesim/Spawn\nArgs: x y theta name\n")
    assert mask(ok(graph, "uri", "spawn")) == "rosrpc://<host>:<port>\n"
    assert ok(graph, "args", "/spawn") == "x y theta name\n"
    assert ok(graph, "args", "/clear") == "\n"
    assert ok(graph, "find", "std_srvs/Empty") == "/clear\n"
    assert ok(graph, "find", "nosuch/Type") == "\n"


def test_unknown_service(graph: LiveGraph) -> None:
    assert fails(graph, "type", "/nosuch", status=1) == "Unknown service [/nosuch]\n"
    assert fails(graph, "info", "/nosuch", status=1) == "ERROR: unknown service\n"
    assert fails(graph, "uri", "/nosuch", status=1) == "Unknown service: /nosuch\n"
    assert fails(graph, "args", "/nosuch") == "ERROR: Service [/nosuch] is not available.\n"
    assert fails(graph, "call", "/nosuch") == "ERROR: Service [/nosuch] is not available.\n"


def test_call(graph: LiveGraph) -> None:
    assert ok(graph, "call", "/spawn", "2", "2", "0.2", "") == 'name: "turtle2"\n'
    assert ok(graph, "call", "/spawn", "{x: 1, name: leo}") == 'name: "leo"\n'
    assert ok(graph, "call", "/add_two_ints", "{a: 10, b: 20}") == "sum: 30\n"
    assert ok(graph, "call", "-v", "/add_two_ints", "5", "6") == "a: 5\nb: 6\n---\nsum: 11\n"
    assert ok(graph, "call", "/add_two_ints", "--", "-1", "-2") == "sum: -3\n"
    assert ok(graph, "call", "/add_two_ints", "-1", "-2") == "sum: -3\n"
    assert ok(graph, "call", "/clear") == "\n"
    assert ok(graph, "call", "/set_flag", "true") == 'success: True\nmessage: "flag True"\n'


def test_call_reads_yaml_documents_from_stdin(graph: LiveGraph) -> None:
    assert ok(graph, "call", "/add_two_ints", input="a: 1\nb: 2\n---\n[3, 4]\n") == "sum: 3\nsum: 7\n"


def test_call_errors(graph: LiveGraph) -> None:
    assert fails(graph, "call", "/fail") == (
        "ERROR: service [/fail] responded with an error: b'error processing request: it broke'\n")
    assert fails(graph, "call", "/add_two_ints", "1") == (
        "ERROR: Incompatible arguments to call service:\nNot enough arguments:\n * Given: [1]\n"
        " * Expected: ['a', 'b']\nProvided arguments are:\n * 1 (type int)\n\nService arguments are: [a b]\n")
    assert fails(graph, "call", "/add_two_ints", "{c: 1}") == (
        "ERROR: Incompatible arguments to call service:\nNo field name [c]\nProvided arguments are:\n"
        " * {'c': 1} (type dict)\n\nService arguments are: [a b]\n")
    assert fails(graph, "call", "/add_two_ints", "1", "x").startswith(
        "ERROR: Unable to send request. One of the fields has an incorrect type:\n  field b ")
    assert fails(graph, "call", "/add_two_ints", "{a: 1").startswith("ERROR: Invalid YAML in argument [{a: 1]: ")


def test_call_wait(graph: LiveGraph) -> None:
    import subprocess

    from tests.cli.live_graph import BIN

    waiting = subprocess.Popen([str(BIN / "rosservice"), "call", "--wait", "/late/add_two_ints", "2", "3"],
                               env=graph.env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        time.sleep(0.5)
        assert waiting.poll() is None  # silent until the service appears
        graph.start_node("__ns:=/late", "__name:=late")
        out, err = waiting.communicate(timeout=15)
    finally:
        if waiting.poll() is None:
            waiting.kill()
            waiting.wait()
    assert (waiting.returncode, out, err) == (0, "sum: 5\n", "")


@pytest.mark.parametrize("args", [("list",), ("type", "/x"), ("call", "/x"), ("call", "--wait", "/x"), ("find", "a/B")])
def test_no_master(graph: LiveGraph, tmp_path: Path, args: tuple[str, ...]) -> None:
    result = graph.kame("rosservice", *args, env=no_master_env(tmp_path))
    assert (result.returncode, result.stderr) == (2, "ERROR: Unable to communicate with master!\n")


def test_usage(graph: LiveGraph) -> None:
    result = graph.kame("rosservice")
    assert result.returncode == 64 and result.stdout.startswith("Commands:\n\trosservice args")
    result = graph.kame("rosservice", "call")
    assert result.returncode == 2 and result.stderr.endswith("rosservice: error: service must be specified\n")


# ------------------------------------------------------------------ beside Debian's rosservice

debian = pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 is not installed")


@debian
@pytest.mark.parametrize("args", [
    ("list",), ("list", "-n"), ("list", "/graph_node"), ("type", "/set_flag"), ("type", "/nosuch"),
    ("info", "/set_flag"), ("info", "/nosuch"), ("uri", "/set_flag"), ("uri", "/nosuch"), ("args", "/set_flag"),
    ("args", "/nosuch"), ("find", "std_srvs/Empty"), ("find", "std_srvs/SetBool"),
    ("call", "/set_flag", "true"), ("call", "/set_flag", "{data: true}"), ("call", "-v", "/set_flag", "1"),
    ("call", "/clear"), ("call", "/fail"), ("call", "/nosuch"), ("call", "/set_flag", "1", "2"),
    ("call", "/set_flag", "{c: 1}"), ("call", "/graph_node/set_logger_level", "rospy", "debug"),
    ("call", "/graph_node/set_logger_level", "{logger: rospy}"), ("call",), ("bogus",),
])
def test_same_output_as_real_rosservice(graph: LiveGraph, args: tuple[str, ...]) -> None:
    mine = graph.kame("rosservice", *args)
    real = graph.real("rosservice", *args)
    assert (mine.returncode, mask(mine.stdout), mask(mine.stderr)) == (
        real.returncode, mask(real.stdout), mask(real.stderr))


@debian
def test_same_no_master_error_as_real_rosservice(graph: LiveGraph, tmp_path: Path) -> None:
    env = no_master_env(tmp_path)
    import subprocess

    from tests.support import SYSTEM_PYTHON

    real = subprocess.run([SYSTEM_PYTHON, "/usr/bin/rosservice", "list"], env=env, capture_output=True, text=True)
    mine = graph.kame("rosservice", "list", env=env)
    assert (mine.returncode, mine.stderr) == (real.returncode, real.stderr)
