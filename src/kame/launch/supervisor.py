"""The processes of a launch: started, watched, respawned, and stopped with no orphan left.

Rules (roslaunch's nodeprocess and pmon, with its console wording):
- Each child runs in its own session (process group), so a terminal's Ctrl-C reaches only us;
  we stop a child by signalling its group: SIGINT, then after `sigint_timeout` SIGTERM
  (`[name] escalating to SIGTERM`), then after `sigterm_timeout` SIGKILL.
- A child that exits is reported (`[name] process has finished cleanly` in bold, or red
  `process has died [pid, exit code, cmd]`). A respawning child starts again after its
  respawn_delay (`[name] restarting process`); a required one ends the whole launch.
- A respawning child that dies young (within 5 s of its start) twice in a row waits longer
  before each further start: 0.5 s, doubled per young death up to 30 s (or its respawn_delay,
  if longer; kame.net.backoff.RespawnBackoff), said once per step (`[name] died 0.1 s after it started,
  3 times in a row: restarting in 1 s`); a child that lived longer starts the count afresh.
  roslaunch restarts a node that crashes at start as fast as it can, forever.
- On Linux a child is started with PR_SET_PDEATHSIG: if roslaunch is killed outright
  (SIGKILL, a crash), its children get SIGTERM instead of living on as orphans; and a watchdog
  process that outlives roslaunch (kame.net.watchdog) then stops their process groups as
  shutdown does, SIGINT to SIGKILL, so neither a node that ignores SIGTERM nor a shell
  wrapper's child outlives it.
- When every non-core child is gone and nothing will respawn, the monitor ends (unless told to
  keep going, as roslaunch does when it started the master).
- Remote processes (a roslaunch child per other machine) are watched alongside: the launch goes
  on while one of them lives, and shutdown stops them together with the local children.
- Shutdown stops the children in reverse start order, then the core processes (rosout, master);
  `[name] killing on exit` names those still registered: running, respawning, or the required
  one that ended the launch (not those that already ended for good).
"""

from __future__ import annotations

import asyncio
import contextlib
import errno
import logging
import os
import signal
import sys
from collections.abc import Callable
from pathlib import Path
from typing import IO, Protocol

from kame.launch.plan import ProcessSpec
from kame.net.backoff import RespawnBackoff
from kame.net.process import die_with_parent
from kame.net.watchdog import GroupWatchdog

log = logging.getLogger("kame.launch")
BOLD, RED, RESET = "\033[1m", "\033[31m", "\033[0m"


def _write(stream: IO[str], text: str) -> None:
    """A closed terminal or pipe must not stop the launch from stopping its children."""
    try:
        print(text, file=stream, flush=True)
    except (OSError, ValueError):
        pass


def say(text: str) -> None:
    _write(sys.stdout, text)


def say_bold(text: str) -> None:
    _write(sys.stdout, f"{BOLD}{text}{RESET}")


def say_error(text: str) -> None:
    _write(sys.stderr, f"{RED}{text}{RESET}")


class LaunchFailure(Exception):
    """A process that could not even be started (bad launch-prefix, missing program)."""


class Child:
    """One launched process (the same name across respawns)."""

    def __init__(self, spec: ProcessSpec, run_dir: Path | None, core: bool = False) -> None:
        self.spec = spec
        self.run_dir = run_dir
        self.core = core
        self.proc: asyncio.subprocess.Process | None = None
        self.pid = -1
        self.starts = 0
        self.exit_code: int | None = None
        self.stopping = False
        self.gone = False  # exited for good and was not required: pmon unregisters it, shutdown skips it
        self.started_at = 0.0
        self.backoff = RespawnBackoff()

    def respawn_delay(self, now: float) -> float:
        """How long to wait before starting again, the child having just exited at `now`."""
        lived = now - self.started_at
        delay, news = self.backoff.delay(lived, self.spec.node.respawn_delay)
        if news:
            say_error(f"[{self.name}] died {lived:.1f} s after it started, {self.backoff.young_deaths} times "
                      f"in a row: restarting in {delay:g} s")
        return delay

    @property
    def name(self) -> str:
        return self.spec.name

    async def start(self) -> int:
        out: IO[bytes] | None = None
        if self.spec.log_output and self.run_dir is not None:
            self.run_dir.mkdir(parents=True, exist_ok=True)
            out = open(self.run_dir / f"{self.spec.log_name}-stdout.log", "ab" if self.spec.respawn else "wb")
        os.makedirs(self.spec.cwd, exist_ok=True)
        try:
            self.proc = await asyncio.create_subprocess_exec(
                *self.spec.argv, env=dict(self.spec.env), cwd=self.spec.cwd, stdout=out, start_new_session=True,
                preexec_fn=die_with_parent())
        except OSError as exc:
            self.pid, self.exit_code = -1, None
            if exc.errno == errno.ENOEXEC:
                raise LaunchFailure(f"Unable to launch [{self.name}]. \n"
                                    "If it is a script, you may be missing a '#!' declaration at the top.") from exc
            if exc.errno == errno.ENOENT:
                raise LaunchFailure(
                    f"Roslaunch got a '{exc.strerror}' error while attempting to run:\n\n{' '.join(self.spec.argv)}\n\n"
                    "Please make sure that all the executables in this command exist and have\n"
                    "executable permission. This is often caused by a bad launch-prefix.") from exc
            raise LaunchFailure(f"unable to launch [{' '.join(self.spec.argv)}]: {exc.strerror}") from exc
        finally:
            if out is not None:
                out.close()
        self.starts += 1
        self.started_at = asyncio.get_running_loop().time()
        self.exit_code = None
        self.pid = self.proc.pid
        say_bold(f"process[{self.name}]: started with pid [{self.pid}]")
        log.info("process[%s]: started %s with pid %d", self.name, self.spec.argv, self.pid)
        return self.pid

    def exit_description(self) -> str:
        cmd = " ".join(self.spec.argv)
        if self.exit_code is None:
            text = f"process has died without exit code [pid {self.pid}, cmd {cmd}]."
        elif self.exit_code != 0:
            text = f"process has died [pid {self.pid}, exit code {self.exit_code}, cmd {cmd}]."
        else:
            text = "process has finished cleanly"
        if self.run_dir is not None:
            text += f"\nlog file: {self.run_dir / self.spec.log_name}*.log"
        return text

    async def stop(self, sigint_timeout: float, sigterm_timeout: float) -> None:
        self.stopping = True
        proc = self.proc
        if proc is None or proc.returncode is not None:
            return
        steps = ((signal.SIGINT, sigint_timeout, "SIGTERM"), (signal.SIGTERM, sigterm_timeout, "SIGKILL"))
        for sig, timeout, escalation in steps:
            self._signal(sig)
            try:
                await asyncio.wait_for(proc.wait(), timeout)
                return
            except asyncio.TimeoutError:
                say_error(f"[{self.name}] escalating to {escalation}")
        self._signal(signal.SIGKILL)
        await proc.wait()

    def _signal(self, sig: signal.Signals) -> None:
        """To the child's process group (its children too), or the child itself if the group is gone."""
        assert self.proc is not None
        try:
            os.killpg(self.proc.pid, sig)
        except ProcessLookupError:
            with contextlib.suppress(ProcessLookupError):
                os.kill(self.proc.pid, sig)
        except PermissionError:
            with contextlib.suppress(ProcessLookupError):
                os.kill(self.proc.pid, sig)


class RemoteProcess(Protocol):
    """A process on another machine (kame.launch.remote's roslaunch child): watched, stopped with the rest."""

    name: str
    ended: asyncio.Event
    stopping: bool
    gone: bool

    def alive(self) -> bool: ...

    async def stop(self, sigint_timeout: float, sigterm_timeout: float) -> None: ...

    async def exit_description(self) -> str: ...


class Monitor:
    """Watches the children; `run()` returns when the launch is over (or `shutdown_event` is set)."""

    def __init__(self, sigint_timeout: float = 15.0, sigterm_timeout: float = 2.0, keep_alive: bool = False,
                 on_death: Callable[[Child], None] | None = None) -> None:
        self.sigint_timeout = sigint_timeout
        self.sigterm_timeout = sigterm_timeout
        self.keep_alive = keep_alive
        self.on_death = on_death
        self.children: list[Child] = []
        self.core: list[Child] = []
        self.remotes: list[RemoteProcess] = []
        self.done = asyncio.Event()
        self._watchers: list[asyncio.Task[None]] = []
        self._watchdog: GroupWatchdog | None = None  # started with the first child (Linux)

    def _started(self, child: Child) -> None:
        """Hand a child's process group to the watchdog that outlives us."""
        if self._watchdog is None and sys.platform.startswith("linux"):
            self._watchdog = GroupWatchdog(self.sigint_timeout, self.sigterm_timeout)
        if self._watchdog is not None:
            self._watchdog.watch(child.pid, child.name)

    async def add(self, child: Child) -> bool:
        """Start `child` and watch it; False (reported, recorded as dead) when it cannot start."""
        (self.core if child.core else self.children).append(child)
        try:
            await child.start()
        except LaunchFailure as exc:
            say_error(f"RLException: {exc}")
            say_error(f"[{child.name}] {child.exit_description()}")
            (self.core if child.core else self.children).remove(child)
            return False
        self._started(child)
        self._watchers.append(asyncio.ensure_future(self._watch(child)))
        return True

    async def _watch(self, child: Child) -> None:
        while True:
            assert child.proc is not None
            code = await child.proc.wait()
            if self._watchdog is not None:
                self._watchdog.released(child.pid)
            if child.stopping:
                return
            child.exit_code = code
            description = child.exit_description()
            if self.on_death is not None:
                self.on_death(child)
            if child.spec.required and not child.core:
                say_error("=" * 80 + f"REQUIRED process [{child.name}] has died!\n{description}\n"
                          "Initiating shutdown!\n" + "=" * 80)
                self.done.set()
                return
            if code:
                say_error(f"[{child.name}] {description}")
            else:
                say_bold(f"[{child.name}] {description}")
            if not child.spec.respawn:
                child.gone = True
                self._check_all_dead()
                return
            await asyncio.sleep(child.respawn_delay(asyncio.get_running_loop().time()))
            if child.stopping or self.done.is_set():
                return
            say(f"[{child.name}] restarting process")
            try:
                await child.start()
            except LaunchFailure as exc:
                say_error(f"RLException: {exc}")
                child.gone = True
                self._check_all_dead()
                return
            self._started(child)

    def add_remote(self, remote: RemoteProcess) -> None:
        """Watch a started remote process: its end is reported, and it is stopped on shutdown."""
        self.remotes.append(remote)
        self._watchers.append(asyncio.ensure_future(self._watch_remote(remote)))

    async def _watch_remote(self, remote: RemoteProcess) -> None:
        await remote.ended.wait()
        if remote.stopping:
            return
        description = await remote.exit_description()
        if remote.stopping:
            return
        (say_bold if description == "process has finished cleanly" else say_error)(f"[{remote.name}] {description}")
        remote.gone = True
        self._check_all_dead()

    def _alive(self, child: Child) -> bool:
        return child.proc is not None and (child.proc.returncode is None or child.spec.respawn)

    def _check_all_dead(self) -> None:
        if not self.keep_alive and not any(self._alive(c) for c in self.children) and not any(
                r.alive() for r in self.remotes):
            say("all processes on machine have died, roslaunch will exit")
            self.done.set()

    def has_processes(self) -> bool:
        return any(self._alive(c) for c in self.children) or bool(self.core) or any(r.alive() for r in self.remotes)

    async def shutdown(self) -> None:
        """Stop everything: children in reverse start order (together), then core processes in turn."""
        self.done.set()
        for child in reversed(self.children):
            if not child.gone:  # as pmon: one that already ended is no longer listed
                say(f"[{child.name}] killing on exit")
        for remote in reversed(self.remotes):
            if not remote.gone:
                say(f"[{remote.name}] killing on exit")
        await asyncio.gather(*(c.stop(self.sigint_timeout, self.sigterm_timeout) for c in reversed(self.children)),
                             *(r.stop(self.sigint_timeout, self.sigterm_timeout) for r in reversed(self.remotes)))
        for child in reversed(self.core):
            say(f"[{child.name}] killing on exit")
            await child.stop(self.sigint_timeout, self.sigterm_timeout)
        for task in self._watchers:
            task.cancel()
        for task in self._watchers:
            with contextlib.suppress(asyncio.CancelledError):
                await task
        if self._watchdog is not None:
            self._watchdog.close()
            self._watchdog = None
