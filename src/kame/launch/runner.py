"""A whole launch run: the master (started when none answers), rosout, parameters, then the nodes.

Order (roslaunch's ROSLaunchRunner): master (`process[master]`, ROS_MASTER_URI, /run_id), rosout
(`process[rosout-1]`, `started core service [/rosout]`) when we started the master, setup
commands (<rosparam command="delete|dump">), clear_params, parameters, then the nodes in
declaration order. A node that cannot be started is reported and the rest run.
"""

from __future__ import annotations

import asyncio
import getpass
import sys
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import urlsplit

from kame.catkin import executables
from kame.cli.roscore import ROS_DISTRO, ROS_VERSION
from kame.cli.rosmaster import log_dir, ros_home
from kame.launch import plan
from kame.launch.errors import LaunchError, PackageNotFound
from kame.launch.model import LOCAL_ADDRESSES, LaunchConfig, Node, Param
from kame.launch.remote import RemoteChild
from kame.launch.server import LaunchServer, ProcessState
from kame.launch.supervisor import Child, Monitor, say, say_bold, say_error
from kame.net import interfaces
from kame.net.address import is_this_host
from kame.node.master_proxy import MasterError, MasterProxy
from kame.node.remote_poll import REMOTE_POLL_PERIOD
from kame.param_yaml import ParamValueError, check

CALLER = "/roslaunch"
# the core's nodes, which kame runs from its own modules (roscore.xml's rosout has no package here)
CORE_PROGRAMS = {("rosout", "rosout"): (sys.executable, "-m", "kame.cli.rosout")}
MASTER_START_TIMEOUT = 10.0


def core_params() -> list[Param]:
    """What roscore.xml sets: `rosversion roslaunch` and `rosversion -d`, with their newline."""
    return [Param("/rosversion", ROS_VERSION + "\n"), Param("/rosdistro", ROS_DISTRO + "\n")]


def master_answers(uri: str, timeout: float = 1.0) -> bool:
    proxy = MasterProxy(uri, CALLER, timeout=timeout)
    try:
        proxy.call("getPid")
        return True
    except (OSError, MasterError, ValueError):
        return False
    finally:
        proxy.close()


@dataclass
class RunOptions:
    run_id: str
    master_uri: str
    run_dir: Path
    ros_home: Path
    env: Mapping[str, str]
    port: int | None = None  # for an auto-started master
    force_screen: bool = False
    force_log: bool = False
    force_required: bool = False
    local_only: bool = False
    sigint_timeout: float = 15.0
    sigterm_timeout: float = 2.0
    num_workers: int = 3
    master_timeout: float | None = None
    master_logger_level: str | None = None
    is_core: bool = False
    title: str | None = None  # the terminal title (launch files), extended with the master's URI


class LaunchRun:
    def __init__(self, config: LaunchConfig, options: RunOptions,
                 run_command: Callable[[list[str]], int] | None = None) -> None:
        self.config = config
        self.options = options
        self.run_command = run_command
        self.counter = 0
        self.started_master = False
        self.monitor = Monitor(options.sigint_timeout, options.sigterm_timeout, keep_alive=options.is_core)
        self.failed: list[str] = []
        self.succeeded: list[str] = []
        self.server: LaunchServer | None = None  # announced on the parameter server when set

    def process_states(self) -> list[ProcessState]:
        """The launched processes as the roslaunch server reports them (read from its threads)."""
        states = []
        for child in [*self.monitor.core, *self.monitor.children]:
            node = child.spec.node
            alive = child.proc is not None and child.proc.returncode is None and not child.gone
            states.append(ProcessState(child.name, child.starts, alive, args=list(child.spec.argv),
                                       respawn=node.respawn, required=node.required, exit_code=child.exit_code))
        return states

    # ------------------------------------------------------------------ setup

    def check(self) -> None:
        """Everything refused before anything starts: values the server cannot hold, unknown machines."""
        for param in self.config.params.values():
            try:
                check(param.key, param.value)
            except ParamValueError as exc:
                raise LaunchError(str(exc)) from None
        if self.options.local_only:
            return
        for node in (*self.config.nodes, *self.config.tests):
            machine = self.config.machines.get(node.machine_name or "")
            if node.machine_name and machine is None:
                raise LaunchError(f"ERROR: unknown machine [{node.machine_name}]", node.filename, node.line)

    async def setup(self) -> None:
        await self._master()
        proxy = MasterProxy(self.options.master_uri, CALLER)
        try:
            self._run_id(proxy)
            if self.server is not None:
                proxy.call("setParam", self.server.param, self.server.uri)
            if self.started_master:
                await self._core_nodes()
            for exe in self.config.executables:
                self._executable(exe.command, list(exe.args))
            if not self.options.is_core:
                self._parameters(proxy)
        finally:
            proxy.close()

    async def _master(self) -> None:
        uri = self.options.master_uri
        if master_answers(uri):
            if self.options.is_core:
                raise LaunchError("roscore cannot run as another roscore/master is already running. \n"
                                  "Please kill other roscore/master processes before relaunching.\n"
                                  f"The ROS_MASTER_URI is {uri}")
            self._announce(uri)
            return
        parts = urlsplit(uri)
        if parts.hostname not in LOCAL_ADDRESSES and not is_this_host(parts.hostname or ""):
            raise LaunchError(f"ERROR: unable to contact ROS master at [{uri}]\n"
                              "The traceback for the exception was written to the log file")
        port = self.options.port or parts.port or 11311
        say("auto-starting new master")
        argv = [sys.executable, "-m", "kame.cli.rosmaster", "--core", "-p", str(port),
                "-w", str(self.options.num_workers), f"__log:={self.options.run_dir / 'master.log'}"]
        if self.options.master_timeout is not None:
            argv[6:6] = ["-t", str(self.options.master_timeout)]
        if self.options.master_logger_level:
            argv[6:6] = ["--master-logger-level", self.options.master_logger_level]
        spec = plan.ProcessSpec("master", Node("rosmaster", "rosmaster", "master"), tuple(argv),
                                dict(self.options.env), str(self.options.ros_home), True, "master")
        child = Child(spec, self.options.run_dir, core=True)
        if not await self.monitor.add(child):
            raise LaunchError("ERROR: unable to auto-start master process")
        self.started_master = True
        deadline = time.monotonic() + MASTER_START_TIMEOUT
        exited = asyncio.ensure_future(child.proc.wait()) if child.proc is not None else None
        try:
            while not master_answers(uri, 0.5):
                if time.monotonic() > deadline or (exited is not None and exited.done()):
                    raise LaunchError(f"ERROR: could not contact master [{uri}]")
                # a master coming up sends no event: asked again, but a master that dies ends the wait at once
                if exited is not None:
                    await asyncio.wait([exited], timeout=REMOTE_POLL_PERIOD)
                else:
                    await asyncio.sleep(REMOTE_POLL_PERIOD)
        finally:
            if exited is not None:
                exited.cancel()
        self._announce(uri)

    def _announce(self, uri: str) -> None:
        say_bold(f"ROS_MASTER_URI={uri}")
        if self.options.title is not None:
            print(f"\033]2;{self.options.title} {uri}\007", flush=True)  # roslaunch print()s it

    def _run_id(self, proxy: MasterProxy) -> None:
        if not proxy.call("hasParam", "/run_id"):
            say_bold(f"setting /run_id to {self.options.run_id}")
            proxy.call("setParam", "/run_id", self.options.run_id)
            return
        value = proxy.call("getParam", "/run_id")
        if value != self.options.run_id:
            raise LaunchError(f"run_id on parameter server does not match declared run_id: "
                              f"{value} vs {self.options.run_id}")

    async def _core_nodes(self) -> None:
        rosout = Node("rosout", "rosout", "rosout", respawn=True)
        self.counter += 1
        spec = plan.plan_process(rosout, self.counter, list(CORE_PROGRAMS["rosout", "rosout"]), self.options.env,
                                 self.options.master_uri, self.options.run_dir, self.options.ros_home)
        if await self.monitor.add(Child(spec, self.options.run_dir, core=True)):
            say("started core service [/rosout]")
        else:
            say_error("ERROR: cannot launch node of type [rosout/rosout]")

    def _executable(self, command: str, args: list[str]) -> None:
        say(f"running {command} {' '.join(args)}")
        if self.run_command is None or self.run_command([command, *args]) != 0:
            say_error(f"ERROR: {command} {' '.join(args)} failed")

    def _parameters(self, proxy: MasterProxy) -> None:
        for ns in plan.unify_clear_params(self.config.clear_params):
            if proxy.call("hasParam", ns):
                proxy.call("deleteParam", ns)
        for param in self.config.params.values():
            try:
                proxy.call("setParam", param.key, param.value)
            except MasterError as exc:
                raise LaunchError(f"Failed to set parameter: {exc.message}") from None

    # ------------------------------------------------------------------ nodes

    def program(self, node: Node) -> list[str]:
        """The program of `node`; LaunchError in roslaunch's words when there is none."""
        return find_program(node.package, node.type, self.options.env)

    async def launch_node(self, node: Node) -> Child | None:
        if self.options.force_required:
            node.required = True
        try:
            program = self.program(node)
        except LaunchError as exc:
            say_error(f"ERROR: cannot launch node of type [{node.package}/{node.type}]: {exc}")
            self.failed.append(node.name)
            return None
        self.counter += 1
        spec = plan.plan_process(node, self.counter, program, self.options.env, self.options.master_uri,
                                 self.options.run_dir, self.options.ros_home, self.options.force_screen,
                                 self.options.force_log)
        child = Child(spec, self.options.run_dir)
        if await self.monitor.add(child):
            self.succeeded.append(spec.name)
            return child
        self.failed.append(spec.name)
        return None

    def is_local(self, node: Node) -> bool:
        machine = self.config.machines.get(node.machine_name or "")
        return machine is None or machine_is_local(machine.address, machine.user)

    def remote_nodes(self) -> dict[str, list[Node]]:
        """The nodes to run on other machines, by machine name (none with --local)."""
        by_machine: dict[str, list[Node]] = {}
        if not self.options.local_only:
            for node in self.config.nodes:
                if not self.is_local(node):
                    by_machine.setdefault(node.machine_name or "", []).append(node)
        return by_machine

    async def launch_nodes(self) -> None:
        """The other machines' roslaunch children first (a failure ends the launch, as roslaunch's), then ours."""
        for counter, (machine_name, nodes) in enumerate(self.remote_nodes().items()):
            machine = self.config.machines[machine_name]
            child = RemoteChild(f"{machine.address}-{counter}", machine, nodes)
            failure = await child.start(self.options.run_id, self.options.master_uri, self.options.sigint_timeout,
                                        self.options.sigterm_timeout)
            if child.command is not None:
                self.monitor.add_remote(child)
            if failure is not None:
                raise LaunchError(failure)
            self.succeeded.extend(n.name for n in nodes)
        for node in self.config.nodes:
            if self.is_local(node):
                await self.launch_node(node)

    async def spin(self) -> None:
        """Until the launch is over; then everything is stopped."""
        if not self.monitor.has_processes():
            say_bold("No processes to monitor")
        else:
            await self.monitor.done.wait()
        await self.stop()

    async def stop(self) -> None:
        await self.monitor.shutdown()
        say("shutting down processing monitor...")
        say("... shutting down processing monitor complete")

    def withdraw_server(self) -> None:
        """Delete our server's /roslaunch/uris entry from a master that outlives the launch
        (roslaunch leaves it: every launch on a long-running roscore added one more, and roswtf
        then reports them as launches that stopped answering). A master we started ended with
        the launch, its parameters with it."""
        if self.server is None or self.started_master:
            return
        proxy = MasterProxy(self.options.master_uri, CALLER, timeout=2.0)
        try:
            proxy.call("deleteParam", self.server.param)
        except (OSError, MasterError, ValueError):
            pass  # the master went first, or never had it (the launch failed before setting it)
        finally:
            proxy.close()


def find_program(package_name: str, node_type: str, env: Mapping[str, str]) -> list[str]:
    """The argv that runs node `node_type` of `package_name`; LaunchError in roslaunch's words when
    there is none (PackageNotFound for an unknown package)."""
    package = executables.packages(env).get(package_name)
    if package is None and (package_name, node_type) in CORE_PROGRAMS:
        return list(CORE_PROGRAMS[package_name, node_type])
    if package is None:
        raise PackageNotFound("\n".join([package_name, *(f"ROS path [{i}]={p}"
                                                           for i, p in enumerate(executables.ros_paths(env)))]))
    hits = executables.find_node(package, node_type, env)
    if not hits:
        raise LaunchError(f"Cannot locate node of type [{node_type}] in package [{package_name}]. Make sure "
                          "file exists in package path and permission is set to executable (chmod +x)")
    return executables.command_for(hits[0])


def address_is_local(address: str) -> bool:
    """Whether a <machine> at `address` is this host: this host's name, or a name or address
    resolving to a loopback address (127.0.1.1 too) or to one of this host's interfaces."""
    if address in LOCAL_ADDRESSES or is_this_host(address):
        return True
    local = set(interfaces.local_addresses(ipv6=True))
    return any(a.startswith("127.") or a == "::1" or a in local for a in interfaces.resolve(address) or ())


def machine_is_local(address: str, user: str | None) -> bool:
    """Whether a <machine>'s nodes run here rather than over SSH, as roslaunch decides: its
    address is this host and it names no other user (roslaunch's #491: another user on this host
    is reached over SSH, to run as that user)."""
    return address_is_local(address) and (not user or user == getpass.getuser())


def run_dir_of(env: Mapping[str, str], run_id: str) -> Path:
    return log_dir(dict(env)) / run_id


def ros_home_of(env: Mapping[str, str]) -> Path:
    return ros_home(dict(env))
