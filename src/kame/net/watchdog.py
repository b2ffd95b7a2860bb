"""A watchdog that outlives a launch: when roslaunch dies without stopping its children
(SIGKILL, a crash), it stops their process groups as roslaunch's own shutdown would.

Why a process of its own: PR_SET_PDEATHSIG (kame.net.process.die_with_parent) sends SIGTERM
to roslaunch's direct children when it dies, and nothing more, so a node that ignores SIGTERM
lives on, and so does the child of a shell wrapper (the wrapper dies; its child, in the same
process group, hears nothing). Every launched child leads a process group of its own (its
session), so stopping the group stops a wrapper's children too; but no code of a process
killed by SIGKILL runs, and a thread of it dies with it.

How: the launch starts the watchdog first, in a session of its own (a signal to roslaunch's
group does not reach it). Only roslaunch holds the write end of the watchdog's stdin (the pipe
is not inherited by the launched children), and writes `+<pgid> <name>` when a child starts
and `-<pgid>` once that child's group has no process left. The pipe's end (EOF) comes when
roslaunch closes it or dies, however it dies. The watchdog then escalates on every listed group
that still has a process: SIGINT, `sigint_timeout` for them to exit (waited on pidfds, not
polled), SIGTERM, `sigterm_timeout`, SIGKILL; and exits. After a clean shutdown no listed group
has a process left, and it exits at once.

A group is listed until roslaunch sees it empty, so its id cannot be taken by an unrelated group
meanwhile (Linux does not reuse a process id while a group of that id has a process); a group
that empties after its leader was reaped stays listed, which is the one window for such reuse.
"""

from __future__ import annotations

import contextlib
import logging
import os
import select
import signal
import subprocess
import sys
import time

log = logging.getLogger("kame.net.watchdog")


class GroupWatchdog:
    """The launch's end of the watchdog: started at once; `watch` a child's group when it starts,
    `released` when it is empty; `close` when the launch is over."""

    def __init__(self, sigint_timeout: float, sigterm_timeout: float) -> None:
        self._proc = subprocess.Popen(
            [sys.executable, "-m", "kame.net.watchdog", str(os.getpid()), f"{sigint_timeout:g}",
             f"{sigterm_timeout:g}"], stdin=subprocess.PIPE, start_new_session=True)
        assert self._proc.stdin is not None
        self._pipe = self._proc.stdin
        self._broken = False

    @property
    def pid(self) -> int:
        return self._proc.pid

    def watch(self, pgid: int, name: str) -> None:
        self._send(f"+{pgid} {name}\n")

    def released(self, pgid: int) -> None:
        """`pgid` is gone; once its group has no process left, the watchdog forgets it."""
        if group_is_empty(pgid):
            self._send(f"-{pgid}\n")

    def close(self) -> None:
        """The launch is over: the watchdog stops whatever is left in the groups it watches (none
        after a clean shutdown) and exits. It is left to do so: it was made to outlive us."""
        with contextlib.suppress(OSError):
            self._pipe.close()
        with contextlib.suppress(subprocess.TimeoutExpired):
            self._proc.wait(0)  # reaped now when it is already done; else init reaps it after us

    def _send(self, line: str) -> None:
        if self._broken:
            return
        try:
            self._pipe.write(line.encode())
            self._pipe.flush()
        except (BrokenPipeError, ValueError):
            self._broken = True  # someone killed it: the launch goes on, unguarded against its own SIGKILL
            log.warning("the launch's watchdog (pid %d) is gone: its children may outlive a killed roslaunch",
                        self._proc.pid)


def group_is_empty(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return True
    except PermissionError:  # a member that is not ours (setuid): there is one
        return False
    return False


def _members(groups: set[int]) -> dict[int, int]:
    """The living processes in `groups` (zombies are done), from /proc: pid -> its group."""
    found = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat", "rb") as f:
                fields = f.read().rsplit(b")", 1)[1].split()
        except OSError:
            continue  # gone meanwhile
        state, pgid = fields[0], int(fields[2])
        if pgid in groups and state != b"Z":
            found[int(entry)] = pgid
    return found


def _wait_for_exit(pids: list[int], timeout: float) -> None:
    """Until every one of `pids` has exited, at most `timeout` seconds: on their pidfds."""
    poller = select.poll()
    fds = []
    try:
        for pid in pids:
            try:
                fd = os.pidfd_open(pid)
            except ProcessLookupError:
                continue
            fds.append(fd)
            poller.register(fd, select.POLLIN)
        deadline = time.monotonic() + timeout
        left = len(fds)
        while left > 0:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                return
            for fd, _ in poller.poll(remaining * 1000):
                poller.unregister(fd)
                left -= 1
    finally:
        for fd in fds:
            os.close(fd)


def stop_groups(groups: dict[int, str], sigint_timeout: float, sigterm_timeout: float, parent: int) -> None:
    """roslaunch's shutdown, on every group that still has a process."""
    escalation = ((signal.SIGINT, sigint_timeout), (signal.SIGTERM, sigterm_timeout), (signal.SIGKILL, 0.0))
    for sig, timeout in escalation:
        members = _members(set(groups))
        if not members:
            return
        living = set(members.values())
        names = ", ".join(f"[{groups[pgid]}]" for pgid in sorted(living))
        _say(f"roslaunch [{parent}] is gone and left {names} running: sending {sig.name}")
        for pgid in living:
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.killpg(pgid, sig)
        if timeout:
            _wait_for_exit(list(members), timeout)


def _say(text: str) -> None:
    with contextlib.suppress(OSError, ValueError):  # the terminal may have gone with roslaunch
        print(text, file=sys.stderr, flush=True)


def main(argv: list[str]) -> int:
    """`python -m kame.net.watchdog PARENT_PID SIGINT_TIMEOUT SIGTERM_TIMEOUT`, fed on stdin."""
    for sig in (signal.SIGINT, signal.SIGHUP):  # a Ctrl-C or a closed terminal is roslaunch's to handle
        signal.signal(sig, signal.SIG_IGN)
    parent, sigint_timeout, sigterm_timeout = int(argv[0]), float(argv[1]), float(argv[2])
    groups: dict[int, str] = {}
    for line in sys.stdin.buffer:  # until the launch closes the pipe or dies
        kind, _, rest = line.decode("utf-8", "replace").strip().partition(" ")
        if kind.startswith("+"):
            groups[int(kind[1:])] = rest
        elif kind.startswith("-"):
            groups.pop(int(kind[1:]), None)
    stop_groups(groups, sigint_timeout, sigterm_timeout, parent)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
