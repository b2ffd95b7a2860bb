"""roswtf end to end: kame's installed command as a user types it, against live kame graphs
(kame's roscore and kame rospy nodes, every process stopped by its PID): a healthy graph, and
one with a deliberate problem of each kind (a subscription nobody publishes, a subscriber of
the wrong type, a node killed while registered); then without a master, with a broken
environment and broken packages, and beside Debian's real roswtf on the same graph."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from tests.cli.live_graph import BIN, LiveGraph, live_graph, mask, no_master_env
from tests.support import SYSTEM_PYTHON, Proc, free_port, have_debian_ros, ros_env, wait_for_master

WTF_NODE = Path(__file__).with_name("wtf_node.py")
SEP = "=" * 80
W = "\x1b[1mWARNING\x1b[0m "
E = "\x1b[31m\x1b[1mERROR\x1b[0m "
CLEAN_STATIC = (f"No package or stack in the current directory\n{SEP}\nStatic checks summary:\n\n"
                f"No errors or warnings\n{SEP}\n")
ONLINE_HEAD = ("Beginning tests of your ROS graph. These may take a while...\nanalyzing graph...\n"
               "... done analyzing graph\nrunning graph rules...\n... done running graph rules\n\n"
               "Online checks summary:\n\n")
Result = subprocess.CompletedProcess[str]


def clean_env(home: Path, uri: str) -> dict[str, str]:
    """An environment roswtf finds nothing wrong with: a package path, a log dir that exists."""
    env = ros_env(home, uri)
    (home / "log").mkdir(parents=True, exist_ok=True)
    (home / "ws").mkdir(exist_ok=True)
    env["ROS_PACKAGE_PATH"] = str(home / "ws")
    return env


def roswtf(env: dict[str, str], *args: str, cwd: Path | None = None, plugins: bool = False) -> Result:
    """roswtf without its plugins unless asked (test_tf_plugin has tf's; Debian's roswtf here
    finds no tf package to load it from)."""
    chosen = args if plugins else ("--no-plugins", *args)
    return subprocess.run([str(BIN / "roswtf"), *chosen], env=env, cwd=cwd or env["ROS_HOME"], capture_output=True,
                          text=True, timeout=60)


def until(run: Callable[[], Result], done: Callable[[str], bool], timeout: float = 15.0) -> Result:
    """Run roswtf again until `done(stdout)`: connections settle a moment after registration."""
    deadline = time.monotonic() + timeout
    while True:
        result = run()
        if done(result.stdout) or time.monotonic() > deadline:
            return result
        time.sleep(0.2)


def start(graph: LiveGraph, *args: str) -> Proc:
    proc = Proc([sys.executable, str(WTF_NODE), *args], graph.env)
    graph.procs.append(proc)
    proc.wait_line("ready")
    return proc


def blocks(text: str) -> dict[str, list[str]]:
    """The WARNING/ERROR blocks of a report: title -> its item lines."""
    found: dict[str, list[str]] = {}
    current: list[str] = []
    for line in text.splitlines():
        if line.startswith((W, E)):
            current = found.setdefault(line, [])
        elif line.startswith((" * ", "   * ")):
            current.append(line)
    return found


# ------------------------------------------------------------------ a healthy graph


@pytest.fixture(scope="module")
def healthy(tmp_path_factory: pytest.TempPathFactory) -> Iterator[LiveGraph]:
    home = tmp_path_factory.mktemp("wtf_healthy")
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    graph = LiveGraph(home, uri, clean_env(home, uri))
    graph.procs.append(Proc([str(BIN / "roscore"), "-p", str(port)], graph.env))
    try:
        wait_for_master(uri, proc=graph.procs[0])
        start(graph, "--pub", "/chatter=std_msgs/String", "__name:=talker")
        start(graph, "--sub", "/chatter=std_msgs/String", "__name:=listener")
        yield graph
    finally:
        for proc in reversed(graph.procs):
            proc.stop()


def test_healthy_graph(healthy: LiveGraph) -> None:
    expected = f"{CLEAN_STATIC}{ONLINE_HEAD}No errors or warnings\n"
    result = until(lambda: roswtf(healthy.env), lambda out: out == expected)
    assert (result.returncode, result.stdout, result.stderr) == (0, expected, "")


def test_tf_plugin(healthy: LiveGraph) -> None:
    # tf exports tf.tfwtf to roswtf: its first line, and its online check of a second of /tf
    result = roswtf(healthy.env, plugins=True)
    assert result.stdout.startswith(f"Loaded plugin tf.tfwtf\n{CLEAN_STATIC}"), result.stdout
    assert ("... done running graph rules\nrunning tf checks, this will take a second...\n... tf checks complete\n"
            "\nOnline checks summary:\n\n") in result.stdout
    assert result.stdout.endswith(f"{W}No tf messages\n\n"), result.stdout


def test_tf_plugin_on_live_tf_traffic(tmp_path: Path) -> None:
    """Two publishers on /tf that give turtle1 different parents: tf's plugin hears them for its
    second and reports the contention, as tf.tfwtf does for two broadcasters of one frame."""
    with live_graph(tmp_path) as graph:
        graph.env.update(clean_env(tmp_path, graph.uri))
        for parent in ("world", "odom"):
            message = (f"{{transforms: [{{header: {{stamp: now, frame_id: {parent}}}, child_frame_id: turtle1, "
                       f"transform: {{rotation: {{w: 1.0}}}}}}]}}")
            graph.procs.append(Proc([str(BIN / "rostopic"), "pub", "-s", "-r", "20", "/tf", "tf2_msgs/TFMessage",
                                     message, f"__name:=from_{parent}"], graph.env))
        result = until(lambda: roswtf(graph.env, plugins=True),
                       lambda out: "TF multiple authority contention" in out and "TF re-parenting" in out)
    found = blocks(result.stdout)
    reparenting = [items for title, items in found.items() if title.startswith(f"{E}TF re-parenting contention")]
    authority = [items for title, items in found.items() if title.startswith(f"{E}TF multiple authority")]
    assert reparenting and authority, result.stdout
    assert re.fullmatch(r" \* reparenting of \[turtle1\] to \[(world|odom)\] by \[/from_(world|odom)\]",
                        reparenting[0][0]), reparenting
    assert re.fullmatch(r" \* node \[/from_(world|odom)\] publishing transform \[turtle1\] with parent "
                        r"\[(world|odom)\] already published by node \[/from_(world|odom)\]",
                        authority[0][0]), authority
    assert "No tf messages" not in result.stdout and "out-of-date" not in result.stdout, result.stdout


def test_tf_plugins_rules() -> None:
    from kame.cli._wtf import Report, TfMessage, TfTransform, check_tf

    def sent(by: str, *pairs: tuple[str, str], at: float = 100.0, length: float = 1.0) -> TfMessage:
        return TfMessage(tuple(TfTransform(parent, child, at, length) for parent, child in pairs), 100.5, by)

    report = Report()
    check_tf([sent("/a", ("world", "turtle1")), sent("/b", ("odom", "turtle1")), sent("/c", ("x", "y"), ("y", "x")),
              sent("/d", ("world", "late"), at=90.0), sent("/e", ("world", "bent"), length=0.5)], report)
    assert report.warnings == [
        "Received out-of-date/future transforms:\n * receiving transform from [/d] that differed from ROS time by "
        "-10.5s\n",
        "Received non-normalized rotation in transforms:\n * rotation from [world] to [bent] is not unit length, 0.5\n"]
    assert report.errors == [
        "TF re-parenting contention:\n * reparenting of [turtle1] to [odom] by [/b]\n",
        "TF cycle detection::\n * Frame y is in a loop. It's loop has elements:\ny -> x\n"
        " * Frame x is in a loop. It's loop has elements:\nx -> y\n",
        "TF multiple authority contention:\n * node [/b] publishing transform [turtle1] with parent [odom] already "
        "published by node [/a]\n"]
    quiet = Report()
    check_tf([], quiet)
    assert quiet.warnings == ["No tf messages"] and quiet.errors == []


def test_offline(healthy: LiveGraph) -> None:
    result = roswtf(healthy.env, "--offline")
    assert (result.returncode, result.stdout) == (0, f"{CLEAN_STATIC}\nROS Master does not appear to be running.\n"
                                                     f"Online graph checks will not be run.\nROS_MASTER_URI is "
                                                     f"[{healthy.uri}]\n")


# ------------------------------------------------------------------ a graph with problems

UNCONNECTED = f"{W}The following node subscriptions are unconnected:"
MISSING = f"{E}The following nodes should be connected but aren't:"
MISSING_ITEMS = [" * /dead->/rosout (/rosout)", " * /graph_node->/wrong (/chatter)"]


@pytest.fixture(scope="module")
def troubled(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[LiveGraph, Result]]:
    """graph_node's /turtle1/cmd_vel has no publisher, /wrong takes /chatter as Int32, /dead was killed."""
    home = tmp_path_factory.mktemp("wtf_troubled")
    with live_graph(home) as graph:
        graph.env.update(clean_env(home, graph.uri))
        start(graph, "--sub", "/chatter=std_msgs/Int32", "__name:=wrong")
        dead = start(graph, "--pub", "/dead_topic=std_msgs/String", "__name:=dead")
        os.kill(dead.pid, signal.SIGKILL)  # its registrations stay behind
        dead.popen.wait(10)
        result = until(lambda: roswtf(graph.env), lambda out: blocks(out).get(MISSING) == MISSING_ITEMS)
        yield graph, result


def online(result: Result) -> str:
    assert result.returncode == 0, result.stderr
    static, _, rest = result.stdout.partition(ONLINE_HEAD)
    assert static == CLEAN_STATIC
    return rest


def test_unconnected_subscription(troubled: tuple[LiveGraph, Result]) -> None:
    report = online(troubled[1])
    assert report.startswith("Found 1 warning(s).\nWarnings are things that may be just fine, but are sometimes "
                             f"at fault\n\n{UNCONNECTED}\n * /graph_node:\n   * /turtle1/cmd_vel\n\n\n")


def test_type_mismatch(troubled: tuple[LiveGraph, Result]) -> None:
    found = blocks(online(troubled[1]))
    assert found[MISSING] == MISSING_ITEMS
    assert found[f"{E}The following topics have nodes that disagree on the message type:"] == [
        " * /chatter:", "   * /graph_node publishes [std_msgs/String]", "   * /wrong subscribes [std_msgs/Int32]"]


def test_dead_node(troubled: tuple[LiveGraph, Result]) -> None:
    result = troubled[1]
    found = blocks(mask(online(result)))
    assert found[f"{E}Could not contact the following nodes:"] == [" * /dead"]
    assert found[f"{E}Errors connecting to the following services:"] == [
        f" * service [/dead/{name}] appears to be malfunctioning: Unable to communicate with service "
        f"[/dead/{name}], address [rosrpc://<host>:<port>]" for name in ("get_loggers", "set_logger_level")]
    assert mask(result.stderr) == "ERROR: connection refused to [http://<host>:<port>/]\n"


def test_whole_online_report(troubled: tuple[LiveGraph, Result]) -> None:
    assert mask(online(troubled[1])) == (
        "Found 1 warning(s).\nWarnings are things that may be just fine, but are sometimes at fault\n\n"
        f"{UNCONNECTED}\n * /graph_node:\n   * /turtle1/cmd_vel\n\n\n"
        f"Found 4 error(s).\n\n{E}Could not contact the following nodes:\n * /dead\n\n"
        f"{MISSING}\n" + "".join(f"{item}\n" for item in MISSING_ITEMS) + "\n"
        f"{E}Errors connecting to the following services:\n"
        " * service [/dead/get_loggers] appears to be malfunctioning: Unable to communicate with service "
        "[/dead/get_loggers], address [rosrpc://<host>:<port>]\n"
        " * service [/dead/set_logger_level] appears to be malfunctioning: Unable to communicate with service "
        "[/dead/set_logger_level], address [rosrpc://<host>:<port>]\n\n"
        f"{E}The following topics have nodes that disagree on the message type:\n * /chatter:\n"
        "   * /graph_node publishes [std_msgs/String]\n   * /wrong subscribes [std_msgs/Int32]\n\n")


@pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 is not installed")
def test_same_graph_findings_as_real_roswtf(troubled: tuple[LiveGraph, Result]) -> None:
    graph, mine = troubled
    real = until(lambda: subprocess.run([SYSTEM_PYTHON, "/usr/bin/roswtf"], env=graph.env, cwd=graph.home,
                                        capture_output=True, text=True, timeout=60),
                 lambda out: sorted(blocks(out).get(MISSING, [])) == MISSING_ITEMS)
    theirs = blocks(mask(real.stdout.partition(ONLINE_HEAD)[2]))
    theirs[MISSING].sort()  # the real tool's order is a set's
    ours = blocks(mask(online(mine)))
    extra = f"{E}The following topics have nodes that disagree on the message type:"  # kame's own rule
    assert theirs == {
        title: items for title, items in ours.items() if title != extra}
    assert mask(real.stderr).endswith("ERROR: connection refused to [http://<host>:<port>/]\n")


# ------------------------------------------------------------------ no master, bad environment, bad packages


def test_no_master(tmp_path: Path) -> None:
    env = no_master_env(tmp_path)
    env.update(clean_env(tmp_path, env["ROS_MASTER_URI"]))
    result = roswtf(env)
    assert (result.returncode, result.stderr) == (0, "")
    assert result.stdout == (f"{CLEAN_STATIC}\nROS Master does not appear to be running.\n"
                             f"Online graph checks will not be run.\nROS_MASTER_URI is [{env['ROS_MASTER_URI']}]\n")


def test_broken_environment_and_packages(tmp_path: Path) -> None:
    ws = tmp_path / "ws"
    (ws / "bad" / "msg").mkdir(parents=True)
    (ws / "bad" / "package.xml").write_text(
        '<package format="2"><name>bad</name><version>1.0.0</version><description>d</description>'
        '<maintainer email="m@example.com">m</maintainer><license>BSD</license></package>')
    (ws / "bad" / "msg" / "Broken.msg").write_text("int32 x\nfoo bar baz\n")
    (ws / "notxml").mkdir()
    (ws / "notxml" / "package.xml").write_text("<package><name>notxml</name")
    env = ros_env(tmp_path, "foo://nowhere")
    (tmp_path / "log").mkdir()
    env.update(ROS_PACKAGE_PATH=f"{ws}:{tmp_path / 'gone'}", ROS_IP="192.0.2.254 ")
    result = roswtf(env)
    assert result.returncode == 0
    found = blocks(result.stdout)
    assert f"{W}ROS_IP may be incorrect: ROS_IP [192.0.2.254 ] contains whitespace. This is not a valid IP." in found
    assert found[f"{E}Not all paths in ROS_PACKAGE_PATH [{env['ROS_PACKAGE_PATH']}] point to an existing "
                 "directory: "] == [f" * {tmp_path / 'gone'}"]
    assert f"{E}ROS_MASTER_URI [foo://nowhere] is not a valid URL: protocol is not 'http'" in found
    assert [re.sub(r"column \d+", "column N", item) for item in
            found[f"{E}The following packages have an invalid package.xml:"]] == [
        f" * notxml [{ws / 'notxml'}]: not well-formed XML: unclosed token: line 1, column N"]
    assert found[f"{E}The following message and service definitions cannot be loaded:"] == [
        f" * {ws / 'bad' / 'msg' / 'Broken.msg'}:2: invalid declaration 'foo bar baz' (expected 'TYPE NAME' "
        "separated by spaces)"]
    assert result.stdout.endswith(f"{SEP}\n\nROS Master does not appear to be running.\n"
                                  "Online graph checks will not be run.\nROS_MASTER_URI is [foo://nowhere]\n")


def test_in_a_package_folder(tmp_path: Path) -> None:
    pkg = tmp_path / "ws" / "mypkg"
    (pkg / "scripts").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>mypkg</name></package>")
    env = no_master_env(tmp_path)
    env.update(clean_env(tmp_path, env["ROS_MASTER_URI"]))
    result = roswtf(env, cwd=pkg / "scripts")
    assert result.stdout.startswith(f"Package: mypkg\n{SEP}\n")
    assert f"{E}The following packages have an invalid package.xml:\n * mypkg [{pkg}]: " in result.stdout


def test_usage(tmp_path: Path) -> None:
    env = no_master_env(tmp_path)
    result = roswtf(env, "--bogus")
    assert (result.returncode, result.stderr) == (2, "Usage: roswtf [launch file]\n\nroswtf: error: no such option: "
                                                     "--bogus\n")
    result = roswtf(env, "nosuch.launch")
    assert (result.returncode, result.stdout, result.stderr) == (
        0, "", "Unable to load roslaunch file [nosuch.launch]: Invalid roslaunch XML syntax: [Errno 2] No such file "
               "or directory: 'nosuch.launch'\n")


# ------------------------------------------------------------------ clocks of other machines


class SkewedNode:
    """A node's XML-RPC server on a machine whose clock runs 30 s ahead (its answers' Date says so)."""

    def __init__(self) -> None:
        import threading
        from xmlrpc.server import SimpleXMLRPCRequestHandler, SimpleXMLRPCServer

        class Ahead(SimpleXMLRPCRequestHandler):
            def date_time_string(self, timestamp: float | None = None) -> str:
                return super().date_time_string(time.time() + 30)

        self.server = SimpleXMLRPCServer(("127.0.0.1", 0), Ahead, logRequests=False)
        self.server.register_function(lambda *args: [1, "", os.getpid()], "getPid")
        self.server.register_function(lambda *args: [1, "", []], "getBusInfo")
        self.server.register_function(lambda *args: [1, "", [["/skewed_topic", "std_msgs/String"]]],
                                      "getPublications")
        self.server.register_function(lambda *args: [1, "", []], "getSubscriptions")
        self.server.register_function(lambda *args: [1, "", 0], "publisherUpdate")
        self.uri = f"http://127.0.0.1:{self.server.server_address[1]}/"
        self.thread = threading.Thread(target=self.server.serve_forever, kwargs={"poll_interval": 0.05})
        self.thread.start()

    def close(self) -> None:
        self.server.shutdown()
        self.thread.join()
        self.server.server_close()


def test_a_node_whose_machine_clock_is_off_is_a_warning(tmp_path: Path) -> None:
    import xmlrpc.client

    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = clean_env(tmp_path, uri)
    master = Proc([str(BIN / "rosmaster"), "--core", "-p", str(port)], env)
    node = SkewedNode()
    try:
        wait_for_master(uri, proc=master)
        xmlrpc.client.ServerProxy(uri).registerPublisher("/skewed", "/skewed_topic", "std_msgs/String", node.uri)
        result = roswtf(env)
        title = (f"{W}The clocks of these machines differ from this machine's (time stamps, tf and rosbag compare "
                 "them; synchronise the machines' clocks, with chrony or ntpd):")
        [line] = blocks(result.stdout)[title]
        assert re.fullmatch(r" \* 127\.0\.0\.1 \(node /skewed\): (29|30)\.\d s ahead of this machine", line), line
    finally:
        node.close()
        master.stop()
