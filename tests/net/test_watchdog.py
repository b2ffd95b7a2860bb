"""The launch's watchdog (kame.net.watchdog): the groups it was given are stopped, SIGINT to
SIGKILL, once its pipe ends; groups released empty are forgotten."""

from __future__ import annotations

import os
import signal
import subprocess
import sys

import pytest

from kame.net.watchdog import GroupWatchdog, group_is_empty

from ..support import wait_until

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="pidfds and /proc: Linux")

# a group whose leader ignores SIGINT and SIGTERM and whose child, a shell's, hears neither
STUBBORN = "trap '' INT TERM; sleep 60 & echo $!; wait"


def test_a_group_left_when_the_pipe_ends_is_escalated_to_sigkill() -> None:
    group = subprocess.Popen(["sh", "-c", STUBBORN], stdout=subprocess.PIPE, text=True, start_new_session=True)
    assert group.stdout is not None
    sleeper = int(group.stdout.readline())
    watchdog = GroupWatchdog(sigint_timeout=0.2, sigterm_timeout=0.2)
    try:
        watchdog.watch(group.pid, "stubborn-1")
        watchdog.close()  # what roslaunch's death does to the pipe
        assert group.wait(10) == -signal.SIGKILL
        assert os.waitpid(watchdog.pid, 0)[1] == 0
        assert wait_until(lambda: ended(sleeper))  # the shell's child went with it
    finally:
        if not group_is_empty(group.pid):
            os.killpg(group.pid, signal.SIGKILL)
        group.wait()


def ended(pid: int) -> bool:
    """Gone, or a zombie that nobody has reaped yet (its parent died first)."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            return f.read().rsplit(b")", 1)[1].split()[0] == b"Z"
    except FileNotFoundError:
        return True


def test_a_released_group_is_forgotten() -> None:
    quiet = subprocess.Popen(["sleep", "0"], start_new_session=True)
    quiet.wait()
    watchdog = GroupWatchdog(sigint_timeout=5.0, sigterm_timeout=5.0)
    watchdog.watch(quiet.pid, "quiet-1")
    watchdog.released(quiet.pid)
    watchdog.close()
    assert os.waitpid(watchdog.pid, 0)[1] == 0  # at once: nothing left to stop
