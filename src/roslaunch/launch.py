"""roslaunch.launch: ROSLaunchRunner runs a ROSLaunchConfig with roslaunch.pmon's ProcessMonitor and
roslaunch.nodeprocess's processes: the master (started if none answers), /run_id, the core
nodes, the setup commands, the parameters, then the nodes.

Rules (roslaunch's launch, with its console wording; kame's own runner, kame.launch.runner, keeps
the same order and words):
- A master that does not answer and is not on this host is an error; one on this host is
  started (`auto-starting new master`) and waited for, 10 s at most; it says nothing when it
  comes up, so it is asked again every REMOTE_POLL_PERIOD.
- clear_params are deleted (a namespace once, its parents first), then every parameter is set.
- A node whose program cannot be found is reported and counted as failed; the launch goes on.
- <rosparam command="dump|delete"> runs kame's rosparam, under this interpreter.
"""

from __future__ import annotations

import logging
import subprocess
import sys
import threading
import time
import traceback
from typing import Any

import rosgraph
import rosgraph.names
import rosgraph.network
from kame.launch import plan
from kame.launch.runner import master_answers
from kame.launch.server import uri_param
from kame.node.remote_poll import REMOTE_POLL_PERIOD, poll_remote
from roslaunch.core import *  # noqa: F403 (ROS's launch re-exports core's names)
from roslaunch.core import (
    PHASE_SETUP,
    Executable,
    Master,
    Node,
    RLException,
    RosbinExecutable,
    Test,
    get_ros_root,
    is_machine_local,
    printerrlog,
    printlog,
    printlog_bold,
    setup_env,
)
from roslaunch.core import __all__ as _core_names
from roslaunch.nodeprocess import (
    DEFAULT_TIMEOUT_SIGINT,
    DEFAULT_TIMEOUT_SIGTERM,
    NUM_WORKERS,
    LocalProcess,
    create_master_process,
    create_node_process,
)
from roslaunch.pmon import ProcessListener, ProcessMonitor, start_process_monitor
from roslaunch.rlutil import update_terminal_name

__all__ = [*_core_names, "DEFAULT_TIMEOUT_SIGINT", "DEFAULT_TIMEOUT_SIGTERM", "NUM_WORKERS", "ProcessListener",
           "RLTestTimeoutException", "ROSLaunchListener", "ROSLaunchRunner", "ROSRemoteRunnerIF",
           "create_master_process", "create_node_process", "start_process_monitor", "update_terminal_name",
           "validate_master_launch"]

_TIMEOUT_MASTER_START = 10.0
_ID = "/roslaunch"


def _ended(popen: subprocess.Popen[bytes], period: float) -> bool:
    """Whether the process ended within `period` (waited on, not polled)."""
    try:
        popen.wait(period)
        return True
    except subprocess.TimeoutExpired:
        return False


class RLTestTimeoutException(RLException):
    """A test that ran past its time limit."""


def validate_master_launch(m: Master, is_core: bool, is_rostest: bool = False) -> None:
    """Before starting a master at `m`: RLException when it is not on this host (for roslaunch),
    a warning for roscore (or when ROS_MASTER_URI names another host or port)."""
    if not rosgraph.network.is_local_address(m.get_host()):
        if not is_core:
            raise RLException(f"ERROR: unable to contact ROS master at [{m.uri}]")
        printerrlog(f"WARNING: local hostname '{m.get_host()}' does not map to an IP address.\n"
                    "    Your ROS nodes may fail to communicate.\n\n"
                    "    Please use ROS_IP to set the correct IP address to use.")
    if is_core and not is_rostest:
        env_uri = rosgraph.get_master_uri()
        env_host, env_port = rosgraph.network.parse_http_host_and_port(env_uri)
        if not rosgraph.network.is_local_address(env_host):
            printerrlog(f"WARNING: ROS_MASTER_URI [{env_uri}] host is not set to this machine")
        elif env_port != m.get_port():
            printerrlog(f"WARNING: ROS_MASTER_URI port [{env_port}] does not match this roscore [{m.get_port()}]")


class _ROSLaunchListeners(ProcessListener):
    """Hands each death on to every listener; one that raises is logged and the others still hear."""

    def __init__(self) -> None:
        self.process_listeners: list[Any] = []

    def add_process_listener(self, l: Any) -> None:  # noqa: E741 (ROS's name)
        self.process_listeners.append(l)

    def process_died(self, process_name: str, exit_code: int | None) -> None:
        for listener in self.process_listeners:
            try:
                listener.process_died(process_name, exit_code)
            except Exception:
                logging.getLogger("roslaunch").error(traceback.format_exc())


class ROSLaunchListener:
    """Told of each process of the launch that dies, local or remote."""

    def process_died(self, process_name: str, exit_code: int | None) -> None:
        """`process_name` ended with `exit_code` (None: unknown)."""


class ROSRemoteRunnerIF:
    """What ROSLaunchRunner asks of a runner of other machines' nodes (roslaunch.remote's)."""

    def setup(self) -> None:
        """Prepare the children."""

    def add_process_listener(self, l: Any) -> None:  # noqa: E741 (ROS's name)
        """Hear of remote processes dying."""

    def launch_remote_nodes(self) -> tuple[list[str], list[str]]:
        """Have each child launch its nodes: (succeeded, failed)."""
        return [], []


class ROSLaunchRunner:
    """Runs a launch: launch(), then spin() (or spin_once() from a main loop); stop() ends it."""

    def __init__(self, run_id: str, config: Any, server_uri: str | None = None, pmon: ProcessMonitor | None = None,
                 is_core: bool = False, remote_runner: Any = None, is_child: bool = False, is_rostest: bool = False,
                 num_workers: int = NUM_WORKERS, timeout: float | None = None, master_logger_level: str | bool = False,
                 sigint_timeout: float = DEFAULT_TIMEOUT_SIGINT,
                 sigterm_timeout: float = DEFAULT_TIMEOUT_SIGTERM) -> None:
        if run_id is None:
            raise RLException("run_id is None")
        if sigint_timeout <= 0:
            raise RLException(f"sigint_timeout must be a positive number, received {sigint_timeout:f}")
        if sigterm_timeout <= 0:
            raise RLException(f"sigterm_timeout must be a positive number, received {sigterm_timeout:f}")
        self.run_id = run_id
        self.config = config
        self.server_uri = server_uri
        self.is_child = is_child
        self.is_core = is_core
        self.is_rostest = is_rostest
        self.num_workers = num_workers
        self.timeout = timeout
        self.master_logger_level = master_logger_level
        self.logger = logging.getLogger("roslaunch")
        self.pm = pmon or start_process_monitor()
        self.sigint_timeout = sigint_timeout
        self.sigterm_timeout = sigterm_timeout
        self.listeners = _ROSLaunchListeners()
        if self.pm is None:
            raise RLException("unable to initialize roslaunch process monitor")
        if self.pm.is_shutdown:
            raise RLException("bad roslaunch process monitor initialization: process monitor is already dead")
        self.pm.add_process_listener(self.listeners)
        self.remote_runner = remote_runner

    def add_process_listener(self, l: Any) -> None:  # noqa: E741 (ROS's name)
        """Hear of each process that dies (before the processes start)."""
        self.listeners.add_process_listener(l)

    def _load_parameters(self) -> None:
        master = self.config.master.get()
        for ns in plan.unify_clear_params(self.config.clear_params):
            if master.hasParam(_ID, ns)[2]:
                code, msg, _ = master.deleteParam(_ID, ns)
                if code != 1:
                    raise RLException(f"Failed to clear parameter: {msg}")
        for p in self.config.params.values():
            code, msg, _ = master.setParam(_ID, p.key, p.value)
            if code != 1:
                raise RLException(f"Failed to set parameter: {msg}")

    def _launch_nodes(self) -> tuple[list[str], list[str]]:
        succeeded: list[str] = []
        failed: list[str] = []
        for node in [n for n in self.config.nodes if is_machine_local(n.machine)]:
            proc, success = self.launch_node(node)
            (succeeded if success else failed).append(str(proc))
        if self.remote_runner:
            r_succ, r_fail = self.remote_runner.launch_remote_nodes()
            succeeded.extend(r_succ)
            failed.extend(r_fail)
        return succeeded, failed

    def _launch_master(self) -> bool:
        """Start the master if none answers: True when we did."""
        m = self.config.master
        is_running = master_answers(m.uri)
        if self.is_core and is_running:
            raise RLException("roscore cannot run as another roscore/master is already running. \n"
                              "Please kill other roscore/master processes before relaunching.\n"
                              f"The ROS_MASTER_URI is {m.uri}")
        if not is_running:
            validate_master_launch(m, self.is_core, self.is_rostest)
            printlog("auto-starting new master")
            p = create_master_process(self.run_id, m.type, get_ros_root(), m.get_port(), self.num_workers,
                                      self.timeout, master_logger_level=self.master_logger_level,
                                      sigint_timeout=self.sigint_timeout, sigterm_timeout=self.sigterm_timeout)
            assert self.pm is not None
            self.pm.register_core_proc(p)
            if not p.start():
                raise RLException("ERROR: unable to auto-start master process")
            deadline = time.monotonic() + _TIMEOUT_MASTER_START

            def given_up(period: float) -> bool:
                return p.popen is None or _ended(p.popen, period) or time.monotonic() > deadline

            poll_remote(lambda: True if master_answers(m.uri, REMOTE_POLL_PERIOD) else None, given_up)
        if not master_answers(m.uri):
            raise RLException(f"ERROR: could not contact master [{m.uri}]")
        printlog_bold(f"ROS_MASTER_URI={m.uri}")
        update_terminal_name(m.uri)
        master = m.get()
        self._check_and_set_run_id(master, self.run_id)
        if self.server_uri:
            host, port = rosgraph.network.parse_http_host_and_port(self.server_uri)
            master.setParam(_ID, uri_param(host, port), self.server_uri)
        return not is_running

    def _check_and_set_run_id(self, param_server: Any, run_id: str) -> None:
        code, _, val = param_server.hasParam(_ID, "/run_id")
        if code == 1 and not val:
            printlog_bold(f"setting /run_id to {run_id}")
            param_server.setParam(_ID, "/run_id", run_id)
            return
        code, _, val = param_server.getParam(_ID, "/run_id")
        if code != 1:
            raise RLException("ERROR: unable to retrieve /run_id from parameter server")
        if run_id != val:
            raise RLException(f"run_id on parameter server does not match declared run_id: {val} vs {run_id}")

    def _launch_executable(self, e: Executable) -> None:
        """Run `e` to its end; RLException when it cannot run or is killed."""
        cmd = f"{e.command} {' '.join(e.args)}"
        print(f"running {cmd}")
        env = setup_env(None, self.config.machines[""], self.config.master.uri)
        if isinstance(e, RosbinExecutable) and e.command == "rosparam":
            argv = [sys.executable, "-m", "kame.cli.rosparam", *e.args]
        else:
            argv = ["/bin/sh", "-c", cmd]
        try:
            retcode = subprocess.call(argv, env=env)
        except OSError as exc:
            raise RLException(f"command [{cmd}] failed: {exc}") from exc
        if retcode < 0:
            raise RLException(f"command [{cmd}] failed with exit code {retcode}")

    def _launch_setup_executables(self) -> None:
        for e in self.config.executables:
            if getattr(e, "phase", PHASE_SETUP) == PHASE_SETUP:
                self._launch_executable(e)

    def _launch_core_nodes(self) -> None:
        master = self.config.master.get()
        tolaunch = []
        for node in self.config.nodes_core:
            node_name = rosgraph.names.ns_join(node.namespace, node.name)
            code, msg, _ = master.lookupNode(_ID, node_name)
            if code == -1:
                tolaunch.append(node)
            elif code == 1:
                print(f"core service [{node_name}] found")
            else:
                print("WARN: master is not behaving well (unexpected return value when looking up node)",
                      file=sys.stderr)
                self.logger.error("ERROR: master return [%s][%s] on lookupNode call", code, msg)
        for node in tolaunch:
            node_name = rosgraph.names.ns_join(node.namespace, node.name)
            _, success = self.launch_node(node, core=True)
            if not success:
                raise RLException(f"failed to start core service [{node_name}]")
            print(f"started core service [{node_name}]")

    def launch_node(self, node: Node, core: bool = False) -> tuple[LocalProcess | str, bool]:
        """Start `node` here: (its process, True), or (its name, False) when its program cannot be found."""
        from roslaunch.node_args import NodeParamsException

        if node.machine is None:
            node.machine = self.config.machines[""]
        if node.name is None:
            node.name = rosgraph.names.anonymous_name(node.type)
        try:
            process = create_node_process(self.run_id, node, self.config.master.uri,
                                          sigint_timeout=self.sigint_timeout, sigterm_timeout=self.sigterm_timeout)
        except NodeParamsException as exc:
            printerrlog(f"ERROR: cannot launch node of type [{node.package}/{node.type}]: {exc}")
            return (node.name or f"{node.package}/{node.type}"), False
        assert self.pm is not None
        (self.pm.register_core_proc if core else self.pm.register)(process)
        node.process_name = process.name
        success = process.start()
        if not success:
            if node.machine.name:
                printerrlog(f"launch of {node.package}/{node.type} on {node.machine.name} failed")
            else:
                printerrlog(f"local launch of {node.package}/{node.type} failed")
        return process, success

    def is_node_running(self, node: Node) -> bool:
        return bool(node.process_name) and self.pm is not None and self.pm.has_process(node.process_name or "")

    def spin_once(self) -> bool:
        """One round of the monitor's main-thread jobs: False once it is done."""
        return self.pm.mainthread_spin_once() if self.pm else False

    def spin(self) -> None:
        """Until the monitor is done (every process gone, a required one died, or stop()); then stop."""
        if not self.pm or not self.pm.get_active_names():
            printlog_bold("No processes to monitor")
            self.stop()
            return
        self.pm.mainthread_spin()
        self.stop()
        printlog_bold("done")

    def stop(self) -> None:
        """Stop the monitor and with it every process."""
        if self.pm is not None:
            printlog("shutting down processing monitor...")
            self.pm.shutdown()
            self.pm.join()
            self.pm = None
            printlog("... shutting down processing monitor complete")

    def _setup(self) -> None:
        self.config.assign_machines()
        if self.remote_runner:
            self.remote_runner.add_process_listener(self.listeners)
        if self._launch_master():
            self._launch_core_nodes()
        self._launch_setup_executables()
        if not self.is_child:
            self._load_parameters()

    def launch(self) -> tuple[list[str], list[str]]:
        """Set the launch up and start its nodes: (names started, names that failed)."""
        try:
            self._setup()
            return self._launch_nodes()
        except KeyboardInterrupt:
            self.stop()
            raise

    def run_test(self, test: Test) -> None:
        """Run `test` to its end; RLTestTimeoutException past its time limit."""
        _, success = self.launch_node(test)
        if not success:
            raise RLException(f"test [{test.test_name}] failed to launch")
        deadline = time.monotonic() + test.time_limit
        pm = self.pm
        assert pm is not None
        # the monitor sees the test end (it sends no event): asked again every REMOTE_POLL_PERIOD
        while pm.mainthread_spin_once() and self.is_node_running(test):
            if time.monotonic() > deadline:
                raise RLTestTimeoutException(f"max time [{test.time_limit}s] allotted for test [{test.test_name}] "
                                             f"of type [{test.package}/{test.type}]")
            threading.Event().wait(REMOTE_POLL_PERIOD)

