"""Three test hosts (robot, laptop, tablet: network namespaces, tests/support/netns.py) and a master
on robot, as a lab sets them up: each program told its own name by ROS_HOSTNAME.

`Hosts.start` and `Hosts.run` put a program on one host; every process started is stopped by
its PID and every namespace deleted by `close()`.
"""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

from . import Proc, ros_env
from .netns import Host, Lan

BIN = Path(sys.executable).parent
MASTER_URI = "http://robot:11311/"


class Hosts:
    """The three hosts and the master on robot; `start` and `run` put a program on one host."""

    def __init__(self, home: Path) -> None:
        self.home = home
        self.lan = Lan(["robot", "laptop", "tablet"])
        self.procs: list[Proc] = []
        try:
            self.master = self.start("robot", [str(BIN / "rosmaster"), "--core", "-p", "11311"])
            self.run("tablet", [str(BIN / "rosparam"), "set", "/hosts_up", "1"], timeout=20, retry=True)
        except BaseException:
            self.close()
            raise

    def env(self, host: str) -> dict[str, str]:
        env = ros_env(self.home / host, MASTER_URI)
        env["ROS_HOSTNAME"] = host
        env.pop("DISPLAY", None)
        return env

    def host(self, name: str) -> Host:
        return self.lan[name]

    def start(self, host: str, args: list[str], stdin: int | None = None, **env: str) -> Proc:
        """`args` started on `host`; `stdin=subprocess.PIPE` for a program that reads keys (teleop)."""
        proc = Proc(self.lan[host].command(args), {**self.env(host), **env}, cwd=self.home, stdin=stdin)
        self.procs.append(proc)
        return proc

    def run(self, host: str, args: list[str], timeout: float = 20.0, retry: bool = False, **env: str) -> str:
        """`args` run to the end on `host`; with `retry`, again (for at most `timeout`) while they fail."""
        deadline = time.monotonic() + timeout
        while True:
            result = subprocess.run(self.lan[host].command(args), env={**self.env(host), **env}, capture_output=True,
                                    text=True, timeout=timeout, cwd=self.home)
            if result.returncode == 0:
                return result.stdout
            if not retry or time.monotonic() > deadline:
                raise AssertionError(f"{args} on {host} failed ({result.returncode}):\n"
                                     f"{result.stdout}\n{result.stderr}")
            time.sleep(0.1)

    def stop(self, proc: Proc) -> tuple[str, str]:
        self.procs.remove(proc)
        return proc.stop()

    def close(self) -> None:
        for proc in reversed(self.procs):
            proc.stop()
        self.procs.clear()
        self.lan.close()
