"""kame's roscore as a user runs it: banner, core parameters, logs, refusal, Ctrl-C."""

from __future__ import annotations

import os
import re
import signal
import time
import uuid
import xmlrpc.client
from pathlib import Path

from ..support import Proc, free_port, have_debian_ros, kame_command, ros_env, ros_tool, wait_for_master


def test_roscore_banner_params_logs_and_ctrl_c(tmp_path: Path) -> None:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = ros_env(tmp_path, uri)
    core = Proc(kame_command("kame.cli.roscore", "-p", str(port)), env)
    try:
        wait_for_master(uri, proc=core)
        run_line = core.wait_line("setting /run_id to ")
        run_id = re.search(r"setting /run_id to ([0-9a-f-]+)", run_line).group(1)  # type: ignore[union-attr]
        assert uuid.UUID(run_id).version == 1
        master = xmlrpc.client.ServerProxy(uri)
        rosout_pid = int(re.search(r"process\[rosout-1\]: started with pid \[(\d+)\]",  # type: ignore[union-attr]
                                   core.wait_line("process[rosout-1]")).group(1))
        core.wait_line("started core service [/rosout]")
        assert master.getParam("/x", "/run_id")[2] == run_id
        assert master.getParam("/x", "/rosdistro")[2] == "noetic\n"
        assert master.getParam("/x", "/rosversion")[2] == "1.15.15\n"
        # the roslaunch server (spec §11): announced, stored under /roslaunch/uris, answering
        server_uri = re.search(r"started roslaunch server (http://127\.0\.0\.1:(\d+)/)",  # type: ignore[union-attr]
                               core.wait_line("started roslaunch server"))
        uris = master.getParam("/x", "/roslaunch/uris")[2]
        assert uris == {f"host_127_0_0_1__{server_uri.group(2)}": server_uri.group(1)}
        launcher = xmlrpc.client.ServerProxy(server_uri.group(1))
        assert launcher.get_pid() == [1, "", core.pid]
        assert launcher.list_processes() == [1, "processes on parent machine", [[["master", 1], ["rosout-1", 1]], []]]
        assert launcher.process_info("rosout-1")[2]["respawn"] is True
        assert launcher.process_info("nobody") == [-1, "no process by that name", {}]
        assert (tmp_path / f"roscore-{port}.pid").read_text().strip() == str(core.pid)
        assert (tmp_path / "log" / run_id / "master.log").exists()
        assert (tmp_path / "log" / "latest").resolve() == (tmp_path / "log" / run_id).resolve()

        second = Proc(kame_command("kame.cli.roscore", "-p", str(port)), env)
        assert second.popen.wait(15) == 1
        _, err = second.stop()
        assert "roscore cannot run as another roscore/master is already running. \n" in err
        # roslaunch names the master by the advertised host (ROS_HOSTNAME here), as Debian's roscore does
        assert f"The ROS_MASTER_URI is http://127.0.0.1:{port}/\033[0m\n" in err

        if have_debian_ros():
            assert "/rosdistro" in ros_tool("rosparam", "list", env=env).stdout.split()
    finally:
        t0 = time.monotonic()
        out, _ = core.stop()
        stopped = time.monotonic() - t0
    assert stopped < 2.0
    lines = out.splitlines()
    banner = ["SUMMARY", "========", "", "PARAMETERS", " * /rosdistro: noetic", " * /rosversion: 1.15.15", "",
              "NODES", ""]
    start = lines.index("SUMMARY")
    assert lines[start:start + len(banner)] == banner
    assert f"\033[1mROS_MASTER_URI=http://127.0.0.1:{port}/\033[0m" in lines
    assert "... shutting down processing monitor complete" in lines
    rosout_at = lines.index(f"\033[1mprocess[rosout-1]: started with pid [{rosout_pid}]\033[0m")
    assert lines[rosout_at - 1] == f"\033[1msetting /run_id to {run_id}\033[0m"
    # the terminal titles are print()ed: each on a line of its own, as roslaunch's
    announced = f"\033[1mstarted roslaunch server {server_uri.group(1)}\033[0m"
    assert lines[start - 5:start] == ["\033]2;roscore\007", announced, "ros_comm version 1.15.15", "", ""]
    assert lines[rosout_at - 2] == f"\033]2;roscore http://127.0.0.1:{port}/\007"
    assert lines[rosout_at + 1] == "started core service [/rosout]"
    ctrl_c = lines.index("[rosout-1] killing on exit")
    assert lines[ctrl_c:ctrl_c + 4] == ["[rosout-1] killing on exit", "[master] killing on exit",
                                        "shutting down processing monitor...",
                                        "... shutting down processing monitor complete"]
    assert not _alive(rosout_pid)
    assert not (tmp_path / f"roscore-{port}.pid").exists()
    stdout_log = (tmp_path / "log" / run_id / "rosout-1-stdout.log").read_text()
    assert f"logging to {tmp_path / 'log' / run_id / 'rosout.log'}\n" in stdout_log
    assert "re-publishing aggregated messages to /rosout_agg\nsubscribed to /rosout\n" in stdout_log


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    return not Path(f"/proc/{pid}/stat").read_text().split(")")[-1].split()[0] == "Z"


def _wait_registered(master: xmlrpc.client.ServerProxy, node: str, timeout: float = 10.0) -> str:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        code, _, node_uri = master.lookupNode("/test", node)
        if code == 1:
            return str(node_uri)
        time.sleep(0.05)
    raise AssertionError(f"{node} did not register")


def _node_pid(master: xmlrpc.client.ServerProxy, node: str, timeout: float = 10.0) -> int:
    """The PID that the node registered as `node` reports, once it answers (old URIs refuse)."""
    deadline = time.monotonic() + timeout
    while True:
        try:
            return int(xmlrpc.client.ServerProxy(_wait_registered(master, node)).getPid("/test")[2])
        except OSError:
            assert time.monotonic() < deadline, f"{node} does not answer"
            time.sleep(0.05)


def test_roscore_respawns_rosout(tmp_path: Path) -> None:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    core = Proc(kame_command("kame.cli.roscore", "-p", str(port)), ros_env(tmp_path, uri))
    try:
        first = int(re.search(r"process\[rosout-1\]: started with pid \[(\d+)\]",  # type: ignore[union-attr]
                              core.wait_line("process[rosout-1]")).group(1))
        master = xmlrpc.client.ServerProxy(uri)
        assert _node_pid(master, "/rosout") == first
        os.kill(first, signal.SIGKILL)  # a PID roscore told us, of a process our roscore started
        core.wait_line("[rosout-1] restarting process")
        deadline = time.monotonic() + 10
        while sum("process[rosout-1]: started with pid" in line for line in core.out) < 2:
            assert time.monotonic() < deadline, "rosout was not restarted"
            time.sleep(0.05)
        second = int(re.findall(r"process\[rosout-1\]: started with pid \[(\d+)\]", "".join(core.out))[1])
        assert second != first
        assert _node_pid(master, "/rosout") == second  # the new rosout registered in its place
    finally:
        core.stop()
    assert not _alive(second)


def test_rosmaster_refuses_a_busy_port(tmp_path: Path) -> None:
    port = free_port()
    env = ros_env(tmp_path, f"http://127.0.0.1:{port}/")
    first = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), env)
    try:
        wait_for_master(f"http://127.0.0.1:{port}/", proc=first)
        second = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), env)
        assert second.popen.wait(15) == 1
        assert "is already in use" in second.stop()[1]
    finally:
        first.stop()
