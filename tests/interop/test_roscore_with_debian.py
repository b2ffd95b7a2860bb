"""kame's roscore (master + rosout) with Debian's real ROS 1: compiled roscpp nodes, rosnode kill and
cleanup, and log records from a kame rospy node reaching rosout.log and /rosout_agg.

One kame roscore per module; every process is a tests.support.Proc stopped by its PID. The roscpp
peers (tests/interop/cpp/*.cpp) are compiled once per source version into a cache directory under
the system temp dir; without g++ or roscpp's headers those tests are skipped.
"""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
import xmlrpc.client
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
import yaml

from ..support import SYSTEM_PYTHON, Proc, free_port, have_debian_ros, kame_command, ros_env, ros_tool, wait_for_master

pytestmark = pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 (rospy, ros* tools) is not installed")

HERE = Path(__file__).parent
LOG_NODE = HERE / "kame_log_node.py"
PEER = HERE / "ros_peer_node.py"


class Core:
    def __init__(self, home: Path, **extra_env: str) -> None:
        self.home = home
        self.port = free_port()
        self.uri = f"http://127.0.0.1:{self.port}/"
        self.env = {**ros_env(home, self.uri), **extra_env}
        self.proc = Proc(kame_command("kame.cli.roscore", "-p", str(self.port)), self.env)
        self.run_dir: Path | None = None

    def start(self) -> None:
        wait_for_master(self.uri, proc=self.proc)
        self.proc.wait_line("started core service [/rosout]")
        run_id = xmlrpc.client.ServerProxy(self.uri).getParam("/test", "/run_id")[2]
        self.run_dir = self.home / "log" / run_id
        wait_until(lambda: self.master().lookupService("/test", "/rosout/set_logger_level")[0] == 1,
                   "rosout did not come up")

    def master(self) -> xmlrpc.client.ServerProxy:
        return xmlrpc.client.ServerProxy(self.uri)

    def tool(self, name: str, *args: str, check: bool = True) -> str:
        return ros_tool(name, *args, env=self.env, check=check).stdout

    @property
    def rosout_log(self) -> Path:
        assert self.run_dir is not None
        return self.run_dir / "rosout.log"


def wait_until(condition: Callable[[], object], what: str, timeout: float = 15.0) -> None:
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            raise AssertionError(what)
        time.sleep(0.05)


@pytest.fixture(scope="module")
def core(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Core]:
    c = Core(tmp_path_factory.mktemp("ros_home"))
    try:
        c.start()
        yield c
    finally:
        c.proc.stop()


# ------------------------------------------------------------------ roscpp peers


def test_roscpp_talker_and_listener(core: Core, cpp_peers: dict[str, Path]) -> None:
    talker = Proc([str(cpp_peers["talker"])], core.env)
    listener = Proc([str(cpp_peers["listener"])], core.env)
    try:
        listener.wait_line("ready")
        talker.wait_line("ready")
        heard = listener.wait_line("I heard: [hello ")
        assert re.fullmatch(r"I heard: \[hello \d+\]\n", heard)
        wait_until(lambda: sum("I heard" in line for line in listener.out) >= 3, "the listener heard too little")
        numbers = [int(m) for m in re.findall(r"I heard: \[hello (\d+)\]", "".join(listener.out))]
        assert numbers == list(range(numbers[0], numbers[0] + len(numbers)))  # in order, none lost
        # roscpp's ROS_INFO reaches rosout.log through kame's rosout, with roscpp's full source path
        wait_until(lambda: re.search(r"^\d+\.\d{9} INFO /cpp_talker \[\S*talker\.cpp:\d+\(main\)\] "
                                     r"\[topics: [^\]]*/chatter[^\]]*\] hello \d+$",
                                     core.rosout_log.read_text(), re.M), "no roscpp line in rosout.log")
    finally:
        talker.stop()
        listener.stop()


# ------------------------------------------------------------------ rosnode kill / cleanup


def test_rosnode_kill(core: Core) -> None:
    peer = Proc([SYSTEM_PYTHON, str(PEER), "__name:=victim"], core.env)
    try:
        peer.wait_line("ready")
        out = core.tool("rosnode", "kill", "/victim")
        assert "killing /victim" in out and "killed" in out
        assert peer.popen.wait(10) is not None
        wait_until(lambda: "/victim" not in core.tool("rosnode", "list").split(), "/victim still listed")
    finally:
        peer.stop()


def test_rosnode_cleanup(core: Core) -> None:
    peer = Proc([SYSTEM_PYTHON, str(PEER), "__name:=ghost"], core.env)
    try:
        peer.wait_line("ready")
        os.kill(peer.pid, signal.SIGKILL)  # dies without unregistering
        peer.popen.wait(10)
    finally:
        peer.stop()
    assert "/ghost" in core.tool("rosnode", "list").split()
    result = subprocess.run([SYSTEM_PYTHON, "/usr/bin/rosnode", "cleanup"], input="y\n", env=core.env,
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    assert "Unable to contact the following nodes:\n * /ghost\n" in result.stdout
    assert "/rosout" not in result.stdout.split("Please type y or n")[0].split("following nodes:")[1]
    assert result.stdout.rstrip().endswith("done")
    listed = core.tool("rosnode", "list").split()
    assert "/ghost" not in listed and "/rosout" in listed
    assert "/chatter" not in core.tool("rostopic", "list").split()


# ------------------------------------------------------------------ rosout


@pytest.fixture
def log_node(core: Core) -> Iterator[Proc]:
    node = Proc([sys.executable, str(LOG_NODE)], core.env)
    try:
        node.wait_line("ready")
        yield node
    finally:
        node.stop()


LINE = re.compile(r"^(\d+)\.(\d{9}) WARN /lognode \[kame_log_node\.py:(\d+)\(work\)\] (\[topics: ([^\]]*)\] )?"
                  r"warn (\d+)$", re.M)


def test_rospy_logs_reach_rosout_log_and_rosout_agg(core: Core, log_node: Proc) -> None:
    text = core.rosout_log.read_text()
    assert re.match(r"\n\n\d+\.\d{9}  Node Startup\n", text)
    wait_until(lambda: len(LINE.findall(core.rosout_log.read_text())) >= 2, "no lognode lines in rosout.log")
    lines = LINE.findall(core.rosout_log.read_text())
    secs, _nsecs, line, _topics_part, topics, _n = lines[-1]
    assert int(secs) > 1_600_000_000 and int(line) > 0
    assert set(topics.split(", ")) == {"/lt", "/rosout"}
    numbers = [int(found[-1]) for found in lines]
    assert numbers == sorted(numbers)

    out = core.tool("rostopic", "echo", "-n", "1", "/rosout_agg")
    msg = yaml.safe_load(out.split("---")[0])
    assert msg["level"] == 4 and msg["name"] == "/lognode" and msg["function"] == "work"
    assert msg["file"] == "kame_log_node.py" and re.fullmatch(r"warn \d+", msg["msg"])
    assert sorted(msg["topics"]) == ["/lt", "/rosout"]
    info = core.tool("rostopic", "info", "/rosout_agg")
    assert "Type: rosgraph_msgs/Log" in info and " * /rosout (http://127.0.0.1:" in info


def test_omit_topics(core: Core, log_node: Proc) -> None:
    core.tool("rosparam", "set", "/rosout/omit_topics", "true")
    try:
        def omitted() -> bool:
            return any(not found[3] for found in LINE.findall(core.rosout_log.read_text()))

        wait_until(omitted, "/rosout/omit_topics had no effect")
    finally:
        core.tool("rosparam", "set", "/rosout/omit_topics", "false")
    mark = len(LINE.findall(core.rosout_log.read_text()))
    wait_until(lambda: any(found[3] for found in LINE.findall(core.rosout_log.read_text())[mark:]),
               "topics did not come back")


def test_rosout_node_and_its_logger_services(core: Core) -> None:
    info = core.tool("rosnode", "info", "/rosout")
    assert " * /rosout_agg [rosgraph_msgs/Log]" in info
    assert " * /rosout/get_loggers" in info and " * /rosout/set_logger_level" in info
    assert "/rosout/get_loggers" in core.tool("rosservice", "list").split()
    loggers = yaml.safe_load(core.tool("rosservice", "call", "/rosout/get_loggers"))["loggers"]
    assert {"name": "ros", "level": "info"} in loggers
    core.tool("rosservice", "call", "/rosout/set_logger_level", "ros.rosout", "debug")
    loggers = yaml.safe_load(core.tool("rosservice", "call", "/rosout/get_loggers"))["loggers"]
    assert {"name": "ros.rosout", "level": "debug"} in loggers
    bad = ros_tool("rosservice", "call", "/rosout/set_logger_level", "ros", "loud", env=core.env, check=False)
    assert bad.returncode != 0


def test_rosout_file_logging_can_be_disabled(tmp_path: Path) -> None:
    c = Core(tmp_path, ROSOUT_DISABLE_FILE_LOGGING="yes")
    try:
        c.start()
        assert c.run_dir is not None
        assert not c.rosout_log.exists()
        assert "/rosout_agg" in c.tool("rostopic", "list").split()
    finally:
        c.proc.stop()
    stdout_log = (c.run_dir / "rosout-1-stdout.log").read_text()
    assert "logging to" not in stdout_log and "subscribed to /rosout" in stdout_log
