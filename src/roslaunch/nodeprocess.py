"""roslaunch.nodeprocess: LocalProcess (a real OS process for roslaunch.pmon's ProcessMonitor) and
the factories for a node's process (create_node_process) and the master's (create_master_process).

Rules (roslaunch's nodeprocess, with its console wording; kame's supervisor keeps the same):
- A process runs in its own session (process group), and on Linux gets SIGTERM should this
  program die outright (kame.net.process.die_with_parent) when it was started from a thread that
  lives as long as the launch (the main thread, a ProcessMonitor's); the signal is the forking
  thread's, so one started from a server's request thread (a child's `launch`) goes without.
- Its output goes to `<log dir>/<run_id>/<name>-stdout.log` unless output is screen; a node gets
  `__log:=<log dir>/<run_id>/<name>.log`. Its working directory is ROS_HOME, or with cwd="node"
  its program's folder.
- stop() signals the group: SIGINT, after sigint_timeout SIGTERM (`[name] escalating to SIGTERM`),
  after sigterm_timeout SIGKILL, recorded as an error. The waits are on the process's exit.
- The master is kame's (`python -m kame.cli.rosmaster --core -p PORT -w N`), as kame's roslaunch runs it.
"""

from __future__ import annotations

import errno
import logging
import os
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from typing import IO, Any

import rosgraph.names
import rospkg
from kame.net.process import die_with_parent
from roslaunch.core import *  # noqa: F403 (ROS's nodeprocess re-exports core's names)
from roslaunch.core import Master, Node, RLException, is_child_mode, printerrlog, printlog_bold, setup_env
from roslaunch.core import __all__ as _core_names
from roslaunch.node_args import create_local_process_args
from roslaunch.pmon import FatalProcessLaunch, Process, ProcessMonitor
from rosmaster import NUM_WORKERS

__all__ = [*_core_names, "DEFAULT_TIMEOUT_SIGINT", "DEFAULT_TIMEOUT_SIGTERM", "NUM_WORKERS", "FatalProcessLaunch",
           "LocalProcess", "Process", "create_local_process_args", "create_master_process", "create_node_process"]

_logger = logging.getLogger("roslaunch")
DEFAULT_TIMEOUT_SIGINT = 15.0
DEFAULT_TIMEOUT_SIGTERM = 2.0

_counter = 0


def _next_counter() -> int:
    global _counter
    _counter += 1
    return _counter


def create_master_process(run_id: str, type_: str, ros_root: str | None, port: int, num_workers: int = NUM_WORKERS,
                          timeout: float | None = None, master_logger_level: str | bool = False,
                          sigint_timeout: float = DEFAULT_TIMEOUT_SIGINT,
                          sigterm_timeout: float = DEFAULT_TIMEOUT_SIGTERM) -> LocalProcess:
    """The master's process (not started), named `master`, required."""
    if port < 1 or port > 65535:
        raise RLException(f"invalid port assignment: {port}")
    if type_ not in (Master.ROSMASTER, Master.ZENMASTER):
        raise RLException(f"unknown master typ_: {type_}")
    args = [sys.executable, "-m", "kame.cli.rosmaster", "--core", "-p", str(port), "-w", str(num_workers)]
    if timeout is not None:
        args += ["-t", str(timeout)]
    if master_logger_level:
        args += ["--master-logger-level", str(master_logger_level)]
    return LocalProcess(run_id, "rosmaster", "master", args, dict(os.environ), False, False, required=True,
                        sigint_timeout=sigint_timeout, sigterm_timeout=sigterm_timeout)


def create_node_process(run_id: str, node: Node, master_uri: str, sigint_timeout: float = DEFAULT_TIMEOUT_SIGINT,
                        sigterm_timeout: float = DEFAULT_TIMEOUT_SIGTERM) -> LocalProcess:
    """The process of `node` (not started), named `<ns/name>-<N>`; the node needs its machine assigned."""
    machine = node.machine
    if machine is None:
        raise RLException(f"Internal error: no machine selected for node of type [{node.package}/{node.type}]")
    if not node.name:
        raise ValueError("node name must be assigned")
    env = setup_env(node, machine, master_uri)
    name = f"{rosgraph.names.ns_join(node.namespace, node.name)}-{_next_counter()}".lstrip("/")
    args = create_local_process_args(node, machine)
    return LocalProcess(run_id, node.package, name, args, env, node.output != "screen", respawn=node.respawn,
                        respawn_delay=node.respawn_delay, required=node.required, cwd=node.cwd,
                        sigint_timeout=sigint_timeout, sigterm_timeout=sigterm_timeout)


def _death_signal() -> Callable[[], None] | None:
    """die_with_parent when this thread lives as long as the launch (the main thread, a process
    monitor's): the signal is tied to the forking thread, and a process started from a server's
    request thread would get it when that call returns."""
    thread = threading.current_thread()
    if thread is threading.main_thread() or isinstance(thread, ProcessMonitor):
        return die_with_parent()
    return None


class LocalProcess(Process):
    """A process on this machine."""

    def __init__(self, run_id: str | None, package: str, name: str, args: list[str], env: dict[str, str],
                 log_output: bool, respawn: bool = False, respawn_delay: float = 0.0, required: bool = False,
                 cwd: str | None = None, is_node: bool = True, sigint_timeout: float = DEFAULT_TIMEOUT_SIGINT,
                 sigterm_timeout: float = DEFAULT_TIMEOUT_SIGTERM) -> None:
        super().__init__(package, name, args, env, respawn, respawn_delay, required)
        if sigint_timeout <= 0:
            raise RLException(f"sigint_timeout must be a positive number, received {sigint_timeout:f}")
        if sigterm_timeout <= 0:
            raise RLException(f"sigterm_timeout must be a positive number, received {sigterm_timeout:f}")
        self.run_id = run_id
        self.popen: subprocess.Popen[bytes] | None = None
        self.log_output = log_output
        self.started = False
        self.stopped = False
        self.cwd = cwd
        self.log_dir: str | None = None
        self.pid = -1
        self.is_node = is_node
        self.sigint_timeout = sigint_timeout
        self.sigterm_timeout = sigterm_timeout

    def get_info(self) -> dict[str, Any]:
        info = super().get_info()
        info["pid"] = self.pid
        if self.run_id:
            info["run_id"] = self.run_id
        info["log_output"] = self.log_output
        if self.cwd is not None:
            info["cwd"] = self.cwd
        return info

    def _log_name(self) -> str:
        return self.name.replace("/", "-")

    def _configure_logging(self) -> tuple[IO[str] | None, IO[str] | None]:
        log_dir = rospkg.get_log_dir(env=os.environ)
        if self.run_id:
            log_dir = os.path.join(log_dir, self.run_id)
        try:
            os.makedirs(log_dir, exist_ok=True)
        except OSError as exc:
            if exc.errno == errno.EACCES:
                raise RLException(f"unable to create directory for log file [{log_dir}].\n"
                                  "Please check permissions.") from exc
            raise RLException(f"unable to create directory for log file [{log_dir}]: {exc.strerror}") from exc
        self.log_dir = log_dir
        out = err = None
        if self.log_output:
            mode = "a" if self.respawn else "w"
            out = open(os.path.join(log_dir, f"{self._log_name()}-stdout.log"), mode)
            if is_child_mode():
                err = open(os.path.join(log_dir, f"{self._log_name()}-stderr.log"), mode)
        if self.is_node:
            self.args = [a for a in self.args if not a.startswith("__log:=")]
            self.args.append(f"__log:={os.path.join(log_dir, self._log_name() + '.log')}")
        return out, err

    def _cwd(self) -> str:
        if self.cwd == "node":
            return os.path.dirname(self.args[0])
        if self.cwd == "cwd":
            return os.getcwd()
        if self.cwd == "ros-root":
            return rospkg.get_ros_root() or rospkg.get_ros_home()
        return rospkg.get_ros_home()

    def start(self) -> bool:
        """Start it: True once running; FatalProcessLaunch when it cannot be run at all."""
        super().start()
        assert self.lock is not None
        with self.lock:
            self.started = self.stopped = False
            try:
                out, err = self._configure_logging()
            except Exception as exc:  # as ROS: the process still runs, its output unlogged
                printerrlog(f"[{self.name}] ERROR: unable to configure logging [{exc}]")
                out = err = None
            cwd = self._cwd()
            os.makedirs(cwd, exist_ok=True)
            try:
                self.popen = subprocess.Popen(self.args, cwd=cwd, stdout=out, stderr=err, env=self.env,
                                              close_fds=True, start_new_session=True, preexec_fn=_death_signal())
            except OSError as exc:
                self.started = True
                if exc.errno == errno.ENOEXEC:
                    raise FatalProcessLaunch(f"Unable to launch [{self.name}]. \n"
                                             "If it is a script, you may be missing a '#!' declaration at the top."
                                             ) from exc
                if exc.errno == errno.ENOENT:
                    raise FatalProcessLaunch(
                        f"Roslaunch got a '{exc.strerror}' error while attempting to run:\n\n{' '.join(self.args)}\n\n"
                        "Please make sure that all the executables in this command exist and have\n"
                        "executable permission. This is often caused by a bad launch-prefix.") from exc
                raise FatalProcessLaunch(f"unable to launch [{' '.join(self.args)}]: {exc.strerror}") from exc
            finally:
                for f in (out, err):
                    if f is not None:
                        f.close()
            self.started = True
            if self.popen.poll() in (None, 0):
                self.pid = self.popen.pid
                printlog_bold(f"process[{self.name}]: started with pid [{self.pid}]")
                return True
            printerrlog(f"failed to start local process: {' '.join(self.args)}")
            return False

    def is_alive(self) -> bool:
        if not self.started:
            return True
        lock = self.lock
        if lock is not None and not lock.acquire(blocking=False):
            # being stopped (or started): stop() decides how it ended, as ROS's without an exit code;
            # a poll here would catch the SIGINT's status first and report that instead
            return True
        try:
            return self._still_running()
        finally:
            if lock is not None:
                lock.release()

    def _still_running(self) -> bool:
        if self.stopped or self.popen is None:
            if self.time_of_death is None:
                self.time_of_death = time.time()
            return False
        self.exit_code = self.popen.poll()
        if self.exit_code is not None:
            if self.time_of_death is None:
                self.time_of_death = time.time()
            return False
        return True

    def get_exit_description(self) -> str:
        cmd = " ".join(self.args)
        if self.exit_code is None:
            text = f"process has died without exit code [pid {self.pid}, cmd {cmd}]."
        elif self.exit_code != 0:
            text = f"process has died [pid {self.pid}, exit code {self.exit_code}, cmd {cmd}]."
        else:
            text = "process has finished cleanly"
        if self.log_dir:
            text += f"\nlog file: {os.path.join(self.log_dir, self._log_name())}*.log"
        return text

    def _signal_group(self, pgid: int, sig: signal.Signals) -> None:
        try:
            os.killpg(pgid, sig)
        except ProcessLookupError:
            pass

    def _stop_unix(self, errors: list[str]) -> None:
        assert self.popen is not None
        self.exit_code = self.popen.poll()
        if self.exit_code is not None:
            self.popen = None
            self.stopped = True
            return
        pid = self.popen.pid
        try:
            pgid = os.getpgid(pid)
            steps = ((signal.SIGINT, self.sigint_timeout, "SIGTERM"), (signal.SIGTERM, self.sigterm_timeout, "SIGKILL"))
            # as ROS's, the exit status of a process we stopped is not kept: it "died without exit code"
            for sig, timeout, escalation in steps:
                self._signal_group(pgid, sig)
                try:
                    self.popen.wait(timeout)
                    return
                except subprocess.TimeoutExpired:
                    printerrlog(f"[{self.name}] escalating to {escalation}")
            errors.append(f"process[{self.name}, pid {pid}]: required SIGKILL. May still be running.")
            self._signal_group(pgid, signal.SIGKILL)
            self.popen.wait()
        except ProcessLookupError:
            printerrlog(f"no [{self.name}] process with pid [{pid}]")
        finally:
            self.popen = None

    def stop(self, errors: list[str] | None = None) -> None:
        """Stop the process group (see the module's rules); errors are added to `errors`."""
        errors = [] if errors is None else errors
        assert self.lock is not None
        with self.lock:
            try:
                if self.popen is not None:
                    self._stop_unix(errors)
            except Exception:
                _logger.exception("[%s] stopping failed", self.name)
            finally:
                self.stopped = True

