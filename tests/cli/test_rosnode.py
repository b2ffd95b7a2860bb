"""rosnode end to end: kame's installed command against a live kame graph (roscore and kame rospy
nodes), then side by side with Debian's real rosnode on the same graph (ports and PIDs masked).
Plus the pure parts: the info text and script name resolution."""

from __future__ import annotations

import os
import signal
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from kame.cli import _nodeinfo
from kame.cli._tool import script_resolve_name
from tests.cli.live_graph import LiveGraph, live_graph, mask, no_master_env
from tests.support import have_debian_ros

SEP = "-" * 80
GRAPH_NODE_RECORD = (
    "Node [/graph_node]\n"
    "Publications: \n * /chatter [std_msgs/String]\n * /rosout [rosgraph_msgs/Log]\n\n"
    "Subscriptions: \n * /turtle1/cmd_vel [unknown type]\n\n"
    "Services: \n * /add_two_ints\n * /clear\n * /fail\n * /graph_node/get_loggers\n"
    " * /graph_node/set_logger_level\n * /set_flag\n * /spawn\n"
)


@pytest.fixture(scope="module")
def graph(tmp_path_factory: pytest.TempPathFactory) -> Iterator[LiveGraph]:
    with live_graph(tmp_path_factory.mktemp("rosnode")) as g:
        yield g


def ok(graph: LiveGraph, *args: str, input: str | None = None) -> str:
    result = graph.kame("rosnode", *args, input=input)
    assert result.returncode == 0, result.stderr
    return result.stdout


def user_nodes(graph: LiveGraph) -> list[str]:
    return [n for n in ok(graph, "list").split() if n != "/rosout"]


def test_list(graph: LiveGraph) -> None:
    assert "/graph_node" in ok(graph, "list").splitlines()
    assert ok(graph, "list", "/graph_node") == "/graph_node\n"
    assert ok(graph, "list", "/nowhere") == "\n"
    all_line = [line for line in ok(graph, "list", "-a").splitlines() if line.endswith("/graph_node")]
    assert [mask(line) for line in all_line] == ["http://<host>:<port>/ \t/graph_node"]
    assert mask(ok(graph, "list", "-u", "/graph_node")) == "http://<host>:<port>/\n"


def test_info(graph: LiveGraph) -> None:
    out = mask(ok(graph, "info", "/graph_node"))
    assert out.startswith(f"{SEP}\n{GRAPH_NODE_RECORD}\n\ncontacting node http://<host>:<port>/ ...\nPid: <pid>\n")
    assert ok(graph, "info", "-q", "graph_node") == f"{SEP}\n{GRAPH_NODE_RECORD}\n"


def test_info_unknown_node(graph: LiveGraph) -> None:
    result = graph.kame("rosnode", "info", "/nosuch")
    assert result.returncode == 0
    assert result.stdout == (f"{SEP}\nNode [/nosuch]\nPublications: None\n\nSubscriptions: None\n\n"
                             "Services: None\n\n")
    assert result.stderr == "cannot contact [/nosuch]: unknown node\n"


def test_ping(graph: LiveGraph) -> None:
    assert mask(ok(graph, "ping", "-c", "2", "/graph_node")) == (
        "rosnode: node is [/graph_node]\npinging /graph_node with a timeout of 3.0s\n"
        "xmlrpc reply from http://<host>:<port>/\ttime=<t>ms\nxmlrpc reply from http://<host>:<port>/\ttime=<t>ms\n"
        "ping average: <t>ms\n")
    result = graph.kame("rosnode", "ping", "-c", "1", "nosuch")
    assert (result.returncode, result.stdout, result.stderr) == (
        0, "rosnode: node is [/nosuch]\n", "cannot ping [/nosuch]: unknown node\n")


def test_ping_all(graph: LiveGraph) -> None:
    out = mask(ok(graph, "ping", "--all"))
    assert out.startswith("Will ping the following nodes: \n")
    assert " * /graph_node\n" in out
    assert "pinging /graph_node with a timeout of 3.0s\nxmlrpc reply from http://<host>:<port>/\ttime=<t>ms\n" in out


def test_machine(graph: LiveGraph) -> None:
    assert ok(graph, "machine") == "127.0.0.1\n"
    assert "/graph_node" in ok(graph, "machine", "127.0.0.1").split()


def test_kill(graph: LiveGraph) -> None:
    victim = graph.start_node("__name:=victim")
    assert ok(graph, "kill", "/victim") == "killing /victim\nkilled\n"
    victim.popen.wait(10)
    out, err = victim.stop()  # exited already: this waits for the reader threads to take the last lines
    # rospy prints the request's message on stdout, as it is, and logs no warning about it
    assert "shutdown request: user request\n" in out.splitlines(keepends=True)
    assert "shutdown request" not in err, err
    assert "/victim" not in user_nodes(graph)
    result = graph.kame("rosnode", "kill", "/nosuch", "/graph_node")
    assert (result.returncode, result.stdout, result.stderr) == (1, "", "ERROR: Unknown node(s):\n * /nosuch\n")


def test_kill_a_port_of_a_cpp_program_prints_roscpps_warnings(graph: LiveGraph) -> None:
    from tests.support import Proc
    from tests.turtlesim.sim import BIN, wait_until

    mimic = Proc([str(BIN / "rosrun"), "turtlesim", "mimic", "__name:=cpp_victim"], dict(graph.env, NO_COLOR="1"))
    graph.procs.append(mimic)
    wait_until(lambda: "/cpp_victim" in user_nodes(graph), timeout=20, what="mimic registered")
    assert ok(graph, "kill", "/cpp_victim") == "killing /cpp_victim\nkilled\n"
    mimic.popen.wait(10)
    out, err = mimic.stop()
    warnings = [line.split("]: ", 1) for line in err.splitlines() if line.startswith("[ WARN] [")]
    assert [text for _, text in warnings] == ["Shutdown request received.", "Reason given for shutdown: [user request]"]
    assert "shutdown request" not in out


def test_kill_from_the_menu(graph: LiveGraph) -> None:
    victim = graph.start_node("__name:=a_victim")
    out = ok(graph, "kill", input="x\n1\n")
    assert out.startswith("1. /a_victim\n2. /graph_node")
    assert "\n\nPlease enter the number of the node you wish to kill.\n> " in out
    assert out.endswith("ERROR: please enter a number (ctrl-C to cancel)\nkilling /a_victim\nkilled\n")
    victim.popen.wait(10)


def test_cleanup(graph: LiveGraph) -> None:
    assert ok(graph, "cleanup") == ""  # everybody answers: nothing to ask
    dead = graph.start_node("__name:=dead")
    os.kill(dead.pid, signal.SIGKILL)  # its registrations stay behind
    dead.popen.wait(10)
    prompt = ("Unable to contact the following nodes:\n * /dead\n"
              "Warning: these might include alive and functioning nodes, e.g. in unstable networks.\n"
              "Cleanup will purge all information about these nodes from the master.\n"
              "Please type y or n to continue:\n")
    result = graph.kame("rosnode", "cleanup", input="n\n")
    assert result.stdout == prompt + "aborting\n"
    assert "ERROR: connection refused to [http://" in result.stderr
    assert "/dead" in user_nodes(graph)
    assert ok(graph, "cleanup", input="maybe\ny\n") == prompt + "Unregistering /dead\ndone\n"
    assert "/dead" not in user_nodes(graph)


@pytest.mark.parametrize("args", [("list",), ("info", "/x"), ("ping", "/x"), ("kill", "/x"), ("machine",)])
def test_no_master(graph: LiveGraph, tmp_path: Path, args: tuple[str, ...]) -> None:
    result = graph.kame("rosnode", *args, env=no_master_env(tmp_path))
    assert result.returncode == 1
    assert result.stderr == "ERROR: Unable to communicate with master!\n"


def test_usage(graph: LiveGraph) -> None:
    result = graph.kame("rosnode")
    assert result.returncode == 64 and result.stdout.startswith("rosnode is a command-line tool")
    result = graph.kame("rosnode", "info")
    assert result.returncode == 2
    assert result.stderr.endswith("rosnode: error: You must specify at least one node name\n")


# ------------------------------------------------------------------ pure parts


def test_info_text_types_come_from_published_topics() -> None:
    state = ([("/a", ["/n"]), ("/b", ["/m"])], [("/b", ["/n"]), ("/c", ["/n"])], [])
    text = _nodeinfo.describe("/n", state, [["/a", "x/A"], ["/b", "x/B"]])
    assert text == ("Node [/n]\nPublications: \n * /a [x/A]\n\nSubscriptions: \n * /b [x/B]\n * /c [unknown type]\n"
                    "\nServices: None\n")


def test_connections_text() -> None:
    state = ([("/t", ["/pub"])], [("/t", ["/n"])], [])
    uris = {"/pub": "http://h:1/"}
    bus = [[1, "http://h:1/", "i", "TCPROS", "/t", True, "x"],
           [2, "/sub", "o", "TCPROS", "/t", 1, "TCPROS connection on port 5 to [1.2.3.4:6 on socket 7]"],
           [3, "/gone", "o", "TCPROS", "/t", False]]
    assert _nodeinfo.connections(42, bus, state, uris.get) == (
        "Pid: 42\nConnections:\n * topic: /t\n    * to: /pub (http://h:1/)\n    * direction: inbound\n"
        "    * transport: TCPROS\n * topic: /t\n    * to: /sub\n    * direction: outbound (5 - 1.2.3.4:6) [7]\n"
        "    * transport: TCPROS\n")
    assert _nodeinfo.connections(1, [], state, uris.get) == "Pid: 1\n"


def test_connections_say_what_their_queues_dropped() -> None:
    # kame's getBusStats: publication rows with a fifth field (dropped), subscription rows with
    # roscpp's drop estimate; rospy's -1 and roscpp's publication rows (fifth field 0, an int
    # where rospy's fourth is a bool) count nothing
    kame = [[["/t", 10, [[2, 10, 5, True, 3]]]], [["/u", [[1, 20, 9, 4, True]]]], [0, 0, 0]]
    assert _nodeinfo.drop_counts(kame) == {2: 3, 1: 4}
    rospy = [[["/t", 10, [[2, 10, 5, True]]]], [["/u", [[1, 20, 9, -1, True]]]], [0, 0, 0]]
    roscpp = [[["/t", [[2, 10, 8, 5, 0]]]], [["/u", [[0, 60, 42, 7, 0]]]]]
    assert _nodeinfo.drop_counts(rospy) == {} and _nodeinfo.drop_counts(roscpp) == {0: 7}
    assert _nodeinfo.drop_counts("nonsense") == {}
    state = ([("/t", ["/n"])], [("/u", ["/n"])], [])
    bus = [[1, "http://h:1/", "i", "TCPROS", "/u", True], [2, "/sub", "o", "TCPROS", "/t", True]]
    assert _nodeinfo.connections(42, bus, state, {}.get, {1: 4, 2: 0}) == (
        "Pid: 42\nConnections:\n * topic: /u\n    * to: http://h:1/\n    * direction: inbound\n"
        "    * transport: TCPROS\n    * dropped: 4 (its queue was full)\n * topic: /t\n    * to: /sub\n"
        "    * direction: outbound\n    * transport: TCPROS\n")


@pytest.mark.parametrize(("ns", "name", "resolved"), [
    ("/", "x", "/x"), ("/", "/a//b", "/a//b"), ("/ns", "x", "/ns/x"), ("/ns", "~p", "/ns/rosparam/p"), ("/", "", "/"),
])
def test_script_resolve_name(ns: str, name: str, resolved: str) -> None:
    assert script_resolve_name("rosparam", name, {"ROS_NAMESPACE": ns}) == resolved


# ------------------------------------------------------------------ beside Debian's rosnode

debian = pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 is not installed")


@debian
@pytest.mark.parametrize("args", [
    ("list",), ("list", "-a"), ("list", "-u"), ("list", "/graph"), ("info", "/graph_node"),
    ("info", "-q", "/graph_node"),
    ("info", "/nosuch"), ("ping", "-c", "2", "/graph_node"), ("ping", "-c", "1", "/nosuch"), ("ping",), ("machine",),
    ("machine", "127.0.0.1"), ("kill", "/nosuch"), ("bogus",), ("--help",), ("ping", "-a", "-c", "2"),
])
def test_same_output_as_real_rosnode(graph: LiveGraph, args: tuple[str, ...]) -> None:
    mine = graph.kame("rosnode", *args)
    real = graph.real("rosnode", *args)
    assert (mine.returncode, mask(mine.stdout), mask(mine.stderr)) == (
        real.returncode, mask(real.stdout), mask(real.stderr))


@debian
def test_real_rosnode_kills_and_describes_kame_nodes_and_kame_describes_real_connections(graph: LiveGraph) -> None:
    victim = graph.start_node("__name:=real_victim")
    real = graph.real("rosnode", "kill", "/real_victim")
    assert real.stdout == "killing /real_victim\nkilled\n"
    victim.popen.wait(10)
    # a real rospy subscriber connected to kame's publisher: both tools describe both ends alike
    from tests.support import Proc

    echo = Proc(["/usr/bin/python3", "/usr/bin/rostopic", "echo", "-n", "1000", "/chatter"], graph.env)
    graph.procs.append(echo)
    echo.wait_line("data")
    subscriber = next(n for n in user_nodes(graph) if n.startswith("/rostopic_"))
    for node in ("/graph_node", subscriber):
        deadline = time.monotonic() + 20  # each round runs both tools: a second or two under load
        while True:
            mine = mask(ok(graph, "info", node))
            theirs = mask(graph.real("rosnode", "info", node).stdout)
            if mine == theirs or time.monotonic() > deadline:
                break
        assert mine == theirs
        assert "Connections:\n" in mine and " * topic: /chatter\n" in mine
    echo.stop()
