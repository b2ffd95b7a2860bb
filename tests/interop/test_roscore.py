"""kame's roscore as a user runs it: banner, core parameters, logs, refusal, Ctrl-C."""

from __future__ import annotations

import re
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
        assert master.getParam("/x", "/run_id")[2] == run_id
        assert master.getParam("/x", "/rosdistro")[2] == "noetic\n"
        assert master.getParam("/x", "/rosversion")[2] == "1.15.15\n"
        assert (tmp_path / f"roscore-{port}.pid").read_text().strip() == str(core.pid)
        assert (tmp_path / "log" / run_id / "master.log").exists()
        assert (tmp_path / "log" / "latest").resolve() == (tmp_path / "log" / run_id).resolve()

        second = Proc(kame_command("kame.cli.roscore", "-p", str(port)), env)
        assert second.popen.wait(15) == 1
        _, err = second.stop()
        assert "roscore cannot run as another roscore/master is already running. \n" in err
        assert f"The ROS_MASTER_URI is http://localhost:{port}/" in err

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
    assert "started core service" not in out  # rosout comes with the client runtime
    assert not (tmp_path / f"roscore-{port}.pid").exists()


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
