"""A live turtlesim for the tests: kame's master and a headless turtlesim_node, with runners for
kame's installed commands. Every process is a tests.support.Proc, stopped by its PID."""

from __future__ import annotations

import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from tests.support import Proc, free_port, ros_env, wait_for_master

BIN = Path(sys.executable).parent


@dataclass
class Sim:
    home: Path
    uri: str
    env: dict[str, str]
    procs: list[Proc] = field(default_factory=list)

    def run(self, tool: str, *args: str, check: bool = True, timeout: float = 30.0,
            env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
        result = subprocess.run([str(BIN / tool), *args], env=env or self.env, capture_output=True, text=True,
                                timeout=timeout, cwd=self.home)
        if check and result.returncode != 0:
            raise AssertionError(f"{tool} {args} failed ({result.returncode}):\n{result.stdout}\n{result.stderr}")
        return result

    def start(self, *args: str, env: dict[str, str] | None = None, wait: str | None = None) -> Proc:
        proc = Proc([str(BIN / "rosrun"), *args], env or self.env, cwd=self.home)
        self.procs.append(proc)
        if wait is not None:
            proc.wait_line(wait)
        return proc

    def echo(self, topic: str) -> dict[str, Any]:
        out = self.run("rostopic", "echo", "-n", "1", topic, timeout=30).stdout
        data = yaml.safe_load(out.split("---")[0])
        assert isinstance(data, dict), out
        return data

    def pose(self, turtle: str = "turtle1") -> dict[str, Any]:
        return self.echo(f"/{turtle}/pose")


def wait_until(predicate: Callable[[], bool], timeout: float = 30.0, what: str = "condition") -> None:
    deadline = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {what}")
        time.sleep(0.05)


@contextmanager
def master(home: Path) -> Iterator[Sim]:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = ros_env(home, uri)
    core = Proc([str(BIN / "rosmaster"), "--core", "-p", str(port)], env)
    sim = Sim(home, uri, env, [core])
    try:
        wait_for_master(uri, proc=core)
        yield sim
    finally:
        for proc in reversed(sim.procs):
            proc.stop()


@contextmanager
def turtlesim_with_rosout(home: Path) -> Iterator[Sim]:
    """A master with rosout and a headless turtlesim: a graph that logs, as the rqt tools see one."""
    with master(home) as sim:
        sim.procs.append(Proc([str(BIN / "rosout")], sim.env))
        sim.start("turtlesim", "turtlesim_node", "--headless", wait="runs without a window")
        yield sim


@contextmanager
def turtlesim(home: Path) -> Iterator[tuple[Sim, Proc]]:
    with master(home) as sim:
        node = sim.start("turtlesim", "turtlesim_node", "--headless", wait="runs without a window")
        yield sim, node
