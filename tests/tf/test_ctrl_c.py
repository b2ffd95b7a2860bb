"""Ctrl-C ends kame's long-running programs promptly while their main thread waits for their
stop event (a SignalSafeEvent: the kernel may give the SIGINT to another thread, and the wait
still lets the handler run; tests/net/test_signal_wake.py forces that case)."""

from __future__ import annotations

import signal

import pytest

from ..support import Proc, kame_command
from .graph import Graph


@pytest.mark.parametrize(("args", "ready"), [
    (["kame.cli.rosrun", "tf2_ros", "static_transform_publisher", "0", "0", "1", "0", "0", "0", "a", "b"],
     "Spinning until killed"),
    (["kame.cli.rosout"], "logging to"),
])
def test_sigint_ends_the_program_within_two_seconds(graph: Graph, args: list[str], ready: str) -> None:
    proc: Proc = graph.start(kame_command(*args))
    proc.wait_line(ready)
    proc.popen.send_signal(signal.SIGINT)
    try:
        returncode = proc.popen.wait(2.0)
    finally:
        graph.procs.remove(proc)
        out, err = proc.stop()
    assert returncode == 0, f"{out}\n{err}"
