"""roslaunch.pmon: the process monitor of roslaunch's API. Process is what it watches (LocalProcess,
roslaunch.nodeprocess, is a real OS process), ProcessMonitor is a thread that reports each
process that dies, respawns it after its delay or, for a required one, ends the watch, then
stops what is left; ProcessListener hears of each death.

Rules (roslaunch's pmon, with its console wording):
- A Process says it died only through is_alive() (a process of another program sends no event),
  so the monitor asks each one every REMOTE_POLL_PERIOD (0.1 s, as roslaunch); registering a
  process or shutting down wakes it at once.
- A dead process is reported (`[name] process has finished cleanly` in bold, or red), told to
  the listeners, then respawned once its should_respawn() delay is over, or else unregistered and
  kept as a DeadProcess. A required one ends the watch (`REQUIRED process [name] has died!`).
- After registrations_complete(), the monitor ends when no process is left
  (`all processes on machine have died, roslaunch will exit`).
- On ending, the other processes are stopped together (`[name] killing on exit`), then the core
  ones one by one in reverse order; errors they record are printed as `Shutdown errors:`.
- As ROS's, creating a Process in the main thread installs pmon's SIGINT/SIGTERM/SIGHUP handler
  (rl_signal: stop every monitor, then the handler it replaced) and an atexit hook.
"""

from __future__ import annotations

import atexit
import logging
import signal
import sys
import threading
import time
import traceback
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from queue import Empty, Queue
from threading import Lock, RLock, Thread
from types import FrameType
from typing import Any

from kame.node.remote_poll import REMOTE_POLL_PERIOD
from roslaunch.core import RLException, printerrlog, printlog, printlog_bold

__all__ = ["DeadProcess", "Empty", "FatalProcessLaunch", "Lock", "NonFatalProcessLaunch", "Process",
           "ProcessListener", "ProcessMonitor", "Queue", "RLock", "Thread", "logger", "pmon_shutdown",
           "printerrlog", "printlog", "printlog_bold", "rl_signal", "shutdown_process_monitor",
           "start_process_monitor"]

logger = logging.getLogger("roslaunch.pmon")
KILLERS = 10  # processes stopped at once on shutdown, as roslaunch's killer threads


class FatalProcessLaunch(RLException):
    """A process that could not start, and would not on a second try."""


class NonFatalProcessLaunch(RLException):
    """A process could not start; the launch goes on."""


_pmons: list[ProcessMonitor] = []
_pmon_counter = 0
_shutdown_lock = Lock()
_shutting_down = False


def start_process_monitor() -> ProcessMonitor | None:
    """A new ProcessMonitor, started (None once the program is shutting down)."""
    global _pmon_counter
    if _shutting_down:
        return None
    _pmon_counter += 1
    process_monitor = ProcessMonitor(f"ProcessMonitor-{_pmon_counter}")
    with _shutdown_lock:
        _pmons.append(process_monitor)
        process_monitor.start()
    return process_monitor


def shutdown_process_monitor(process_monitor: ProcessMonitor | None) -> bool:
    """Stop `process_monitor` and wait for it: False if it was not running or did not end. Never raises."""
    try:
        if process_monitor is None or process_monitor.is_shutdown:
            return False
        process_monitor.shutdown()
        process_monitor.join(20.0)
        if process_monitor.is_alive():
            logger.error("shutdown_process_monitor: ProcessMonitor shutdown failed!")
            return False
        return True
    except Exception as exc:  # shutdown-critical, as ROS's: reported, never raised
        print(f"exception in shutdown_process_monitor: {exc}", file=sys.stderr)
        traceback.print_exc()
        return False


def pmon_shutdown() -> None:
    """Stop every monitor start_process_monitor made."""
    with _shutdown_lock:
        for p in _pmons:
            shutdown_process_monitor(p)
        del _pmons[:]


SignalHandler = Callable[[int, FrameType | None], Any] | int | None
_signal_chain: dict[int, SignalHandler] = {}
_signal_list = [signal.SIGTERM, signal.SIGINT, signal.SIGHUP]
_sig_initialized = False


def rl_signal(sig: int, stackframe: FrameType | None) -> None:
    """pmon's signal handler: stop every monitor, then run the handler it replaced."""
    global _shutting_down
    if _shutting_down:
        return
    _shutting_down = True
    pmon_shutdown()
    prev_handler = _signal_chain.get(sig)
    if callable(prev_handler) and prev_handler is not rl_signal:
        try:
            prev_handler(sig, stackframe)
        except KeyboardInterrupt:
            pass  # as ROS: Python's default SIGINT handler's exception is filtered out


def _init_signal_handlers() -> None:
    global _sig_initialized
    if _sig_initialized or threading.current_thread() is not threading.main_thread():
        return
    for s in _signal_list:
        _signal_chain[s] = signal.signal(s, rl_signal)
    atexit.register(pmon_shutdown)
    _sig_initialized = True


class Process:
    """A process for ProcessMonitor; subclasses start and stop it (LocalProcess, roslaunch.nodeprocess)."""

    def __init__(self, package: str, name: str, args: list[str], env: dict[str, str], respawn: bool = False,
                 respawn_delay: float = 0.0, required: bool = False) -> None:
        self.package = package
        self.name = name
        self.args = args
        self.env = env
        self.respawn = respawn
        self.respawn_delay = respawn_delay
        self.required = required
        self.lock: Lock | None = Lock()
        self.exit_code: int | None = None
        self.spawn_count = 0
        self.time_of_death: float | None = None
        _init_signal_handlers()

    def __str__(self) -> str:
        return f"Process<{self.name}>"

    def get_info(self) -> dict[str, Any]:
        info = {"spawn_count": self.spawn_count, "args": self.args, "env": self.env, "package": self.package,
                "name": self.name, "alive": self.is_alive(), "respawn": self.respawn,
                "respawn_delay": self.respawn_delay, "required": self.required}
        if self.exit_code is not None:
            info["exit_code"] = self.exit_code
        return info

    def start(self) -> Any:
        self.time_of_death = None
        self.spawn_count += 1

    def is_alive(self) -> bool:
        if self.time_of_death is None:
            self.time_of_death = time.time()
        return False

    def should_respawn(self) -> float | bool:
        """False if it is not to respawn, else the seconds until it may (<= 0: now)."""
        if not self.respawn:
            return False
        if self.time_of_death is None and self.is_alive():
            return False
        assert self.time_of_death is not None
        return (self.time_of_death + self.respawn_delay) - time.time()

    def stop(self, errors: list[str] | None = None) -> None:
        """Stop the process; significant errors are added to `errors`."""

    def get_exit_description(self) -> str:
        if self.exit_code is None:
            return "process has died"
        return f"process has died [exit code {self.exit_code}]" if self.exit_code else "process has finished cleanly"


class DeadProcess(Process):
    """What is kept of a process that died and will not respawn."""

    def __init__(self, p: Process) -> None:
        super().__init__(p.package, p.name, p.args, p.env, p.respawn, p.respawn_delay)
        self.exit_code = p.exit_code
        self.lock = None
        self.spawn_count = p.spawn_count
        self.info = p.get_info()

    def get_info(self) -> dict[str, Any]:
        return self.info

    def start(self) -> Any:
        raise Exception("cannot call start on a dead process!")

    def is_alive(self) -> bool:
        return False


class ProcessListener:
    """Told of each process of a launch that dies (whether or not it is respawned)."""

    def process_died(self, process_name: str, exit_code: int | None) -> None:
        """`process_name` (`talker-2`) ended with `exit_code` (None: killed without one)."""


class ProcessMonitor(Thread):
    """Watches registered processes in its own thread until shut down (see the module's rules)."""

    def __init__(self, name: str = "ProcessMonitor") -> None:
        super().__init__(name=name, daemon=True)
        self.procs: list[Process] = []
        self.plock = RLock()
        self.is_shutdown = False
        self.done = False
        self.reacquire_signals: set[int] = set()
        self.listeners: list[ProcessListener] = []
        self.dead_list: list[DeadProcess] = []
        self.core_procs: list[Process] = []
        self._registrations_complete = False
        self._wake = threading.Event()  # registration, shutdown: look again now
        self._main_jobs = threading.Event()  # for mainthread_spin: signals to take back, or the end

    def add_process_listener(self, l: ProcessListener) -> None:  # noqa: E741 (ROS's name)
        self.listeners.append(l)

    def register(self, p: Process) -> None:
        """Watch `p`; RLException for a second process of its name, or after shutdown."""
        with self.plock:
            if self.has_process(p.name):
                raise RLException(f"cannot add process with duplicate name '{p.name}'")
            if self.is_shutdown:
                raise RLException(f"cannot add process [{p.name}] after process monitor has been shut down")
            self.procs.append(p)
        self._wake.set()

    def register_core_proc(self, p: Process) -> None:
        """Watch a core process: stopped after all others, in reverse order of registration."""
        self.register(p)
        self.core_procs.append(p)

    def registrations_complete(self) -> None:
        """From now on the monitor ends once no process is left."""
        self._registrations_complete = True
        self._wake.set()

    def unregister(self, p: Process) -> None:
        with self.plock:
            self.procs.remove(p)

    def has_process(self, name: str) -> bool:
        return any(p.name == name for p in self.procs)

    def get_process(self, name: str) -> Process | None:
        with self.plock:
            return next((p for p in self.procs if p.name == name), None)

    def has_main_thread_jobs(self) -> bool:
        return bool(self.reacquire_signals)

    def do_main_thread_jobs(self) -> None:
        """Take back the signals another handler took (main thread only)."""
        for s in list(self.reacquire_signals):
            _signal_chain[s] = signal.signal(s, rl_signal)
            self.reacquire_signals.discard(s)

    def kill_process(self, name: str) -> bool:
        """Stop the process named `name` (still listed until the monitor sees it died); False if none."""
        if not isinstance(name, str):
            raise RLException(f"kill_process takes in a process name but was given: {name}")
        printlog(f"[{name}] kill requested")
        with self.plock:
            p = self.get_process(name)
            if p is None:
                return False
            try:
                p.stop([])
            except Exception:
                logger.error(traceback.format_exc())
            return True

    def shutdown(self) -> None:
        self.is_shutdown = True
        self._wake.set()

    def get_active_names(self) -> list[str]:
        with self.plock:
            return [p.name for p in self.procs]

    def get_process_names_with_spawn_count(self) -> list[list[tuple[str, int]]]:
        """[[(name, spawn count) watched], [(name, spawn count) dead]]."""
        with self.plock:
            return [[(p.name, p.spawn_count) for p in self.procs], [(p.name, p.spawn_count) for p in self.dead_list]]

    def mainthread_spin_once(self) -> bool:
        """Do the main thread's jobs; False once the monitor is done."""
        if self.done:
            return False
        if self.has_main_thread_jobs():
            self.do_main_thread_jobs()
        return True

    def mainthread_spin(self) -> None:
        """Do the main thread's jobs until the monitor is done."""
        while not self.done:
            self._main_jobs.wait()
            self._main_jobs.clear()
            if self.has_main_thread_jobs():
                self.do_main_thread_jobs()

    def run(self) -> None:
        try:
            self._run()
        except Exception:
            logger.error(traceback.format_exc())
            traceback.print_exc()
        finally:
            self._post_run()

    def _reported_dead(self, p: Process, respawn: list[Process]) -> bool:
        """Report `p` if it died: True when it is to be respawned or unregistered."""
        if p.is_alive():
            return False
        description = p.get_exit_description()
        dead = False
        if p.required:
            printerrlog("=" * 80 + f"REQUIRED process [{p.name}] has died!\n{description}\nInitiating shutdown!\n"
                        + "=" * 80)
            self.is_shutdown = True
        elif p not in respawn:
            (printerrlog if p.exit_code else printlog_bold)(f"[{p.name}] {description}")
            dead = True
        for listener in self.listeners:
            listener.process_died(p.name, p.exit_code)
        return dead

    def _run(self) -> None:
        respawn: list[Process] = []
        while not self.is_shutdown:
            with self.plock:
                procs = self.procs[:]
            if _sig_initialized:
                taken = {s for s in _signal_list if signal.getsignal(s) != rl_signal}
                if taken:
                    self.reacquire_signals |= taken
                    self._main_jobs.set()
            dead: list[Process] = []
            for p in procs:
                try:
                    if self._reported_dead(p, respawn):
                        dead.append(p)
                except Exception:
                    traceback.print_exc()
                    dead.append(p)
                if self.is_shutdown:
                    break
            for d in dead:
                try:
                    if d.should_respawn() is not False:
                        respawn.append(d)
                    else:
                        self.unregister(d)
                        d.stop([])
                        with self.plock:
                            self.dead_list.append(DeadProcess(d))
                except Exception:
                    logger.error(traceback.format_exc())
            if self._registrations_complete and dead and not self.procs and not respawn:
                printlog("all processes on machine have died, roslaunch will exit")
                self.is_shutdown = True
            respawn = self._respawn(respawn)
            if not self.is_shutdown:
                self._wake.wait(REMOTE_POLL_PERIOD)
                self._wake.clear()

    def _respawn(self, waiting: list[Process]) -> list[Process]:
        """Restart those whose delay is over; the others are still waiting."""
        still = []
        for r in waiting:
            if self.is_shutdown:
                break
            try:
                delay = r.should_respawn()
                if delay is not False and delay <= 0.0:
                    printlog(f"[{r.name}] restarting process")
                    r.stop([])
                    r.start()
                else:
                    still.append(r)
            except Exception:
                traceback.print_exc()
                logger.error("Restart failed %s", traceback.format_exc())
        return still

    def _post_run(self) -> None:
        self.is_shutdown = True
        with self.plock:
            core_procs = self.core_procs[:]
            others = [p for p in reversed(self.procs) if p not in core_procs]
        errors: list[str] = []
        if others:
            with ThreadPoolExecutor(max_workers=KILLERS, thread_name_prefix="ProcessKiller") as killers:
                for found in killers.map(_kill_process, others):
                    errors.extend(found)
        for p in reversed(core_procs):
            errors.extend(_kill_process(p))
        with self.plock:
            del self.procs[:]
            del self.core_procs[:]
        self.reacquire_signals.clear()
        self.done = True
        self._main_jobs.set()
        if errors:
            printerrlog("Shutdown errors:\n" + "\n".join(f" * {e}" for e in errors))


def _kill_process(p: Process) -> list[str]:
    """Stop `p` as shutdown does; the errors it records."""
    errors: list[str] = []
    try:
        printlog(f"[{p.name}] killing on exit")
        p.stop(errors)
    except Exception:
        traceback.print_exc()
        logger.error(traceback.format_exc())
    return errors
