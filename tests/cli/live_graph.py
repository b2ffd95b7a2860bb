"""A live kame graph for the rosnode/rosparam/rosservice tests: kame's roscore and a kame rospy
node (graph_node.py), with runners for kame's installed commands and Debian's real ones.

Every process is started through tests.support.Proc and stopped by its PID.
"""

from __future__ import annotations

import re
import subprocess
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

from tests.support import SYSTEM_PYTHON, Proc, free_port, ros_env, wait_for_master

BIN = Path(sys.executable).parent
GRAPH_NODE = Path(__file__).with_name("graph_node.py")

Result = subprocess.CompletedProcess[str]

_MASKS = [
    (re.compile(r"http://127\.0\.0\.1:\d+/"), "http://<host>:<port>/"),
    (re.compile(r"rosrpc://127\.0\.0\.1:\d+"), "rosrpc://<host>:<port>"),
    (re.compile(r"Pid: \d+"), "Pid: <pid>"),
    (re.compile(r"time=[\d.]+ms"), "time=<t>ms"),
    (re.compile(r"average: [\d.]+ms"), "average: <t>ms"),
    (re.compile(r"\(\d+ - [\d.:]+\) \[\d+\]"), "(<conn>)"),
]


def mask(text: str) -> str:
    for pattern, replacement in _MASKS:
        text = pattern.sub(replacement, text)
    return text


@dataclass
class LiveGraph:
    home: Path
    uri: str
    env: dict[str, str]
    procs: list[Proc] = field(default_factory=list)

    def kame(self, tool: str, *args: str, input: str | None = None, timeout: float = 30.0,
             env: dict[str, str] | None = None) -> Result:
        return subprocess.run([str(BIN / tool), *args], env=env or self.env, input=input, capture_output=True,
                              text=True, timeout=timeout, cwd=self.home)

    def real(self, tool: str, *args: str, input: str | None = None, timeout: float = 30.0) -> Result:
        return subprocess.run([SYSTEM_PYTHON, f"/usr/bin/{tool}", *args], env=self.env, input=input,
                              capture_output=True, text=True, timeout=timeout, cwd=self.home)

    def start_node(self, *args: str) -> Proc:
        proc = Proc([sys.executable, str(GRAPH_NODE), *args], self.env)
        self.procs.append(proc)
        proc.wait_line("ready")
        return proc


@contextmanager
def live_graph(home: Path) -> Iterator[LiveGraph]:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = ros_env(home, uri)
    core = Proc([str(BIN / "roscore"), "-p", str(port)], env)
    graph = LiveGraph(home, uri, env, [core])
    try:
        wait_for_master(uri, proc=core)
        graph.start_node()
        yield graph
    finally:
        for proc in reversed(graph.procs):
            proc.stop()


def no_master_env(home: Path) -> dict[str, str]:
    """An environment whose master URI points at a port nobody listens on."""
    return ros_env(home, f"http://127.0.0.1:{free_port()}/")
