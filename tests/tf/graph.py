"""The running graph the tf tests use: a kame master, programs started and stopped by PID, and
whether Debian's tf2 is here to talk to."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
import time
import xmlrpc.client
from pathlib import Path

import pytest

from ..support import SYSTEM_PYTHON, Proc, free_port, have_debian_ros, kame_command, ros_env, wait_for_master

DEBIAN_STATIC = "/usr/lib/tf2_ros/static_transform_publisher"
DEBIAN_TF_ECHO = "/usr/lib/tf/tf_echo"


def have_debian_tf2() -> bool:
    return have_debian_ros() and os.path.exists(DEBIAN_STATIC) and subprocess.run(
        [SYSTEM_PYTHON, "-c", "import tf2_ros, tf"], capture_output=True).returncode == 0


debian = pytest.mark.skipif(not have_debian_tf2(), reason="Debian's tf2_ros/tf are not installed")


class Graph:
    def __init__(self, home: Path) -> None:
        self.port = free_port()
        self.uri = f"http://127.0.0.1:{self.port}/"
        self.env = ros_env(home, self.uri)
        self.master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(self.port)), self.env)
        self.procs: list[Proc] = []
        wait_for_master(self.uri, proc=self.master)

    def start(self, args: list[str]) -> Proc:
        proc = Proc(args, self.env)
        self.procs.append(proc)
        return proc

    def kame(self, code: str, *args: str) -> Proc:
        return self.start([sys.executable, "-c", textwrap.dedent(code), *args])

    def real(self, code: str, *args: str) -> Proc:
        return self.start([SYSTEM_PYTHON, "-c", textwrap.dedent(code), *args])

    def wait_for_publishers(self, *topics: str, timeout: float = 30.0) -> None:
        """Until each topic has a publisher registered with the master."""
        master = xmlrpc.client.ServerProxy(self.uri)
        deadline = time.monotonic() + timeout
        while True:
            published = {topic for topic, nodes in master.getSystemState("/test")[2][0] if nodes}
            if published.issuperset(topics):
                return
            assert time.monotonic() < deadline, f"no publisher of {set(topics) - published}"
            time.sleep(0.05)

    def finish(self, proc: Proc, timeout: float = 30) -> str:
        """Wait for a program that ends by itself; its stdout (it must exit 0)."""
        return proc.finish(timeout)[0]

    def stop(self) -> None:
        for proc in reversed(self.procs):
            proc.stop()
        self.master.stop()
