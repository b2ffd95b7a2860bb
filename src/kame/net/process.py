"""Child processes that an asyncio program supervises: started, respawned, stopped by PID.

Rules:
- The owner starts it and the owner stops it: `stop()` sends SIGINT to the child's own PID,
  escalates to SIGKILL after a deadline, and waits for it; nothing is ever found by name.
- A respawning child that exits (or is killed) without our asking is started again after
  `respawn_delay`, as roslaunch does for `respawn="true"`; the owner hears of each start.
- Its stdout goes to a file opened for appending, so a respawn continues the same log;
  stderr stays the parent's.
- A respawning child that dies young, again and again, is restarted ever more slowly
  (kame.net.backoff's `RespawnBackoff`, shared with the launch supervisor): a program that crashes at start
  must not be restarted as fast as it can, for good.
- On Linux it gets SIGTERM when its parent dies (PR_SET_PDEATHSIG, `die_with_parent`), so a
  supervisor killed outright leaves no orphan.
"""

from __future__ import annotations

import asyncio
import contextlib
import ctypes
import logging
import os
import signal
import sys
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

from kame.net.backoff import RespawnBackoff

log = logging.getLogger("kame.net.process")
_PR_SET_PDEATHSIG = 1


def _libc_prctl() -> Callable[..., int] | None:
    if not sys.platform.startswith("linux"):
        return None
    try:
        return ctypes.CDLL(None, use_errno=True).prctl
    except (OSError, AttributeError):
        return None


_prctl = _libc_prctl()  # looked up here: a forked child should only call it


def die_with_parent() -> Callable[[], None] | None:
    """A preexec_fn that has the child get SIGTERM when we (this process) die: Linux only, else
    None. The signal is tied to the forking thread, so fork from one that lives as long as we do
    (an event loop's)."""
    prctl = _prctl
    if prctl is None:
        return None
    parent = os.getpid()

    def preexec() -> None:
        prctl(_PR_SET_PDEATHSIG, signal.SIGTERM)
        if os.getppid() != parent:  # we died between the fork and the prctl
            os.kill(os.getpid(), signal.SIGTERM)

    return preexec


class SupervisedProcess:
    def __init__(self, name: str, args: Sequence[str], env: Mapping[str, str] | None = None, stdout: Path | None = None,
                 respawn: bool = False, respawn_delay: float = 0.0,
                 on_start: Callable[[int, bool], None] | None = None,
                 on_exit: Callable[[int, int], None] | None = None) -> None:
        """`on_start(pid, restarted)` runs after each start, `on_exit(pid, returncode)` after each
        exit we did not ask for."""
        self.name = name
        self.args = list(args)
        self.env = dict(env) if env is not None else None
        self.stdout = stdout
        self.respawn = respawn
        self.respawn_delay = respawn_delay
        self.on_start = on_start
        self.on_exit = on_exit
        self.starts = 0
        self._backoff = RespawnBackoff()
        self._started_at = 0.0
        self._proc: asyncio.subprocess.Process | None = None
        self._watcher: asyncio.Task[None] | None = None
        self._stopping = False

    @property
    def pid(self) -> int | None:
        return self._proc.pid if self._proc is not None else None

    @property
    def running(self) -> bool:
        return self._proc is not None and self._proc.returncode is None

    async def start(self) -> int:
        """Start the child (and its watcher); returns its PID."""
        pid = await self._spawn()
        self._watcher = asyncio.ensure_future(self._watch())
        return pid

    async def _spawn(self) -> int:
        out = None
        if self.stdout is not None:
            self.stdout.parent.mkdir(parents=True, exist_ok=True)
            out = open(self.stdout, "ab")  # the child holds it; our copy closes right after the start
        try:
            self._proc = await asyncio.create_subprocess_exec(
                *self.args, env=self.env, stdin=asyncio.subprocess.DEVNULL, stdout=out, preexec_fn=die_with_parent())
        finally:
            if out is not None:
                out.close()
        restarted = self.starts > 0
        self.starts += 1
        self._started_at = asyncio.get_running_loop().time()
        log.info("started %s with pid %d", self.name, self._proc.pid)
        if self.on_start is not None:
            self.on_start(self._proc.pid, restarted)
        return self._proc.pid

    async def _watch(self) -> None:
        while True:
            proc = self._proc
            assert proc is not None
            code = await proc.wait()
            if self._stopping:
                return
            log.warning("%s (pid %d) exited with %d", self.name, proc.pid, code)
            if self.on_exit is not None:
                self.on_exit(proc.pid, code)
            if not self.respawn:
                return
            lived = asyncio.get_running_loop().time() - self._started_at
            delay, news = self._backoff.delay(lived, self.respawn_delay)
            if news:
                log.warning("%s died %.1f s after it started, %d times in a row: restarting in %g s", self.name,
                            lived, self._backoff.young_deaths, delay)
            await asyncio.sleep(delay)
            if self._stopping:
                return
            try:
                await self._spawn()
            except OSError as exc:
                log.error("cannot restart %s: %s", self.name, exc)
                return

    async def stop(self, timeout: float = 1.5) -> int | None:
        """SIGINT, then SIGKILL if it has not exited within `timeout`; returns its exit status."""
        self._stopping = True
        if self._watcher is not None:
            self._watcher.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await self._watcher
        proc = self._proc
        if proc is None:
            return None
        if proc.returncode is None:
            with contextlib.suppress(ProcessLookupError):
                os.kill(proc.pid, signal.SIGINT)
            try:
                await asyncio.wait_for(proc.wait(), timeout)
            except asyncio.TimeoutError:
                log.warning("%s (pid %d) ignored SIGINT for %.1f s: killing it", self.name, proc.pid, timeout)
                with contextlib.suppress(ProcessLookupError):
                    os.kill(proc.pid, signal.SIGKILL)
                await proc.wait()
        return proc.returncode
