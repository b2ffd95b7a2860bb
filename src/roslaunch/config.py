"""roslaunch.config: ROSLaunchConfig (what launch files declare, as roslaunch's objects) and
load_config_default, over kame's launch loader (kame.launch.loader through kame.cli.roslaunch).

`replay` hands a kame LaunchConfig to any object with roslaunch's add_* methods, as upstream's
loader fills a ROSLaunchConfig (or a test's stand-in for one).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

import rospkg
from kame.launch.model import Executable as ModelExecutable
from kame.launch.model import LaunchConfig
from kame.launch.model import Node as ModelNode
from kame.launch.remote import ENV_LOADER
from kame.launch.runner import core_params
from rosgraph.network import create_local_xmlrpc_uri
from roslaunch.core import (
    PHASE_SETUP,
    Executable,
    Machine,
    Master,
    Node,
    Param,
    RLException,
    RosbinExecutable,
    Test,
    is_machine_local,
    local_machine,
)
from rosmaster import DEFAULT_MASTER_PORT

__all__ = ["DEFAULT_MASTER_PORT", "ROSLaunchConfig", "calculate_env_loader", "get_roscore_filename",
           "load_config_default", "load_roscore", "local_machine", "namespaces_of", "replay"]


def namespaces_of(name: str) -> list[str]:
    """`/a/b/c` -> `['/', '/a', '/a/b']`; ValueError for None, TypeError for a non-string."""
    if name is None:
        raise ValueError("name")
    if not isinstance(name, str):
        raise TypeError("name")
    if not name:
        return ["/"]
    splits = [x for x in name.split("/") if x]
    return ["/"] + ["/" + "/".join(splits[:i]) for i in range(1, len(splits))]


def get_roscore_filename() -> str:
    """The roscore.xml ROS reads: /etc/ros's, else the roslaunch package's. kame's roslaunch and
    load_roscore do not read it: kame's core is declared in code (kame.launch.runner.core_params)."""
    filename = os.path.join(rospkg.get_etc_ros_dir(), "roscore.xml")
    if os.path.isfile(filename):
        return filename
    return os.path.join(rospkg.RosPack().get_path("roslaunch"), "resources", "roscore.xml")


def load_roscore(loader: Any, config: Any, verbose: bool = True) -> None:
    """The core into `config`, as kame's roscore runs it: /rosversion, /rosdistro and rosout."""
    core = LaunchConfig()
    for param in core_params():
        core.add_param(param)
    core.add_node(ModelNode("rosout", "rosout", "rosout", respawn=True), core=True)
    replay(core, config, verbose)


def calculate_env_loader(env: Any = None) -> str:
    """The env-loader of machines that name none: kame's shell/env.sh (ROS's is
    /opt/ros/<distro>/env.sh; kame's sets up kame's environment on the other machine)."""
    return str(ENV_LOADER)


class ROSLaunchConfig:
    """The parameters, nodes, tests, machines and setup commands of a launch."""

    def __init__(self) -> None:
        self.master = Master()
        self.nodes_core: list[Node] = []
        self.nodes: list[Node] = []
        self.tests: list[Test] = []
        self.machines: dict[str, Machine] = {}
        self.params: dict[str, Param] = {}
        self.clear_params: list[str] = []
        self.executables: list[Executable] = []
        self.roslaunch_files: list[str] = []
        self.config_errors: list[str] = []
        self.machines[""] = Machine("", "localhost")  # where nodes without a machine run, as roslaunch has it
        self._assign_machines_complete = False
        self._remote_nodes_present = False

    def add_roslaunch_file(self, f: str) -> None:
        if f not in self.roslaunch_files:
            self.roslaunch_files.append(f)

    def add_config_error(self, msg: str) -> None:
        self.config_errors.append(msg)

    def set_master(self, m: Master) -> None:
        self.master = m

    def add_executable(self, exe: Executable) -> None:
        self.executables.append(exe)

    def add_clear_param(self, param: str) -> None:
        self.clear_params.append(param)

    def add_param(self, p: Param, filename: str | None = None, verbose: bool = True) -> None:
        self.params[p.key] = p

    def add_machine(self, m: Machine, verbose: bool = True) -> bool:
        """False when a machine of that name is there already, the same; RLException when different.
        A machine without an env-loader gets the one kame's roslaunch runs its nodes with."""
        if not m.env_loader:
            m.env_loader = calculate_env_loader()
        known = self.machines.get(m.name)
        if known is not None:
            if known.config_key() != m.config_key():
                raise RLException(f"machine [{m.name}] already added and does not match duplicate entry")
            return False
        self.machines[m.name] = m
        return True

    def add_test(self, test: Test, verbose: bool = True) -> None:
        self.tests.append(test)

    def add_node(self, node: Node, core: bool = False, verbose: bool = True) -> None:
        if node.machine_name and node.machine_name not in self.machines:
            raise RLException(f"ERROR: unknown machine [{node.machine_name}]")
        if node.name:
            resolved = node.namespace + node.name
            if any(n.namespace + (n.name or "") == resolved for n in (*self.nodes, *self.nodes_core)):
                raise RLException(f"roslaunch file contains multiple nodes named [{resolved}].\n"
                                  "Please check all <node> 'name' attributes to make sure they are unique.\n"
                                  "Also check that $(anon id) use different ids.")
        (self.nodes_core if core else self.nodes).append(node)

    def has_remote_nodes(self) -> bool:
        """Whether a node runs on another machine; RLException before assign_machines()."""
        if not self._assign_machines_complete:
            raise RLException("ERROR: has_remote_nodes() cannot be called until prelaunch check is complete")
        return self._remote_nodes_present

    def _select_machine(self, node: Node) -> Machine:
        if not node.machine_name:
            return self.machines[""]
        if node.machine_name not in self.machines:
            raise RLException(f"ERROR: unknown machine [{node.machine_name}]")
        return self.machines[node.machine_name]

    def assign_machines(self) -> None:
        """Set each node's `machine` (core nodes: this one); machines alike but for their name are
        taken as one, the first named. Once only."""
        if self._assign_machines_complete:
            return
        self._assign_machines_complete = True
        for node in self.nodes_core:
            node.machine = self.machines[""]
        unified: dict[str, Machine] = {}
        for node in (*self.nodes, *self.tests):
            machine = self._select_machine(node)
            node.machine = unified.setdefault(machine.config_key(), machine)
        self._remote_nodes_present = any(not is_machine_local(m) for m in unified.values())

    def summary(self, local: bool = False) -> str:
        """The PARAMETERS and NODES summary roslaunch prints before starting."""
        lines = ["", "SUMMARY", "========", "", "PARAMETERS"]
        lines += [f" * {key}: {_shown(self.params[key].value)}" for key in sorted(self.params)]
        lines += ["", "NODES"]
        by_ns: dict[str, list[Node]] = {}
        for node in self.nodes:
            by_ns.setdefault(node.namespace, []).append(node)
        for ns in sorted(by_ns):
            lines.append(f"  {ns}")
            lines += [f"    {n.name} ({n.package}/{n.type})" for n in by_ns[ns]]
        return "\n".join(lines)


def _shown(value: Any) -> str:
    text = str(value)
    return text if len(text) <= 20 else text[:20] + "..."


def _node(model: ModelNode) -> Node:
    kwargs: dict[str, Any] = {"namespace": model.namespace, "machine_name": model.machine_name, "args": model.args,
                              "remap_args": [list(r) for r in model.remap_args], "env_args": list(model.env_args),
                              "cwd": model.cwd, "launch_prefix": model.launch_prefix, "filename": model.filename}
    if model.test_name is not None:
        return Test(model.test_name, model.package, model.type, name=model.name, time_limit=model.time_limit,
                    retry=model.retry, **kwargs)
    return Node(model.package, model.type, name=model.name, respawn=model.respawn, respawn_delay=model.respawn_delay,
                output=model.output, required=model.required, **kwargs)


def _executable(exe: ModelExecutable) -> Executable:
    """A setup command of kame's loader (rosparam dump/delete) as roslaunch's loader makes it."""
    return RosbinExecutable(exe.command, exe.args, PHASE_SETUP)


def replay(config: LaunchConfig, ros_config: Any, verbose: bool = False) -> None:
    """Hand what kame's loader read to `ros_config` through roslaunch's add_* methods."""
    for f in config.files:
        ros_config.add_roslaunch_file(f)
    for machine in config.machines.values():
        ros_config.add_machine(Machine(machine.name, machine.address, env_loader=machine.env_loader,
                                       ssh_port=machine.ssh_port, user=machine.user, password=machine.password,
                                       assignable=machine.assignable, timeout=machine.timeout), verbose)
    for param in config.params.values():
        ros_config.add_param(Param(param.key, param.value), verbose=verbose)
    for name in config.clear_params:
        ros_config.add_clear_param(name)
    for exe in config.executables:
        ros_config.add_executable(_executable(exe))
    for node in config.core_nodes:
        ros_config.add_node(_node(node), core=True, verbose=verbose)
    for node in config.nodes:
        ros_config.add_node(_node(node), verbose=verbose)
    for test in config.tests:
        ros_config.add_test(_node(test), verbose)
    for error in config.errors:
        ros_config.add_config_error(error)


def load_config_default(roslaunch_files: Sequence[Any], port: int | None, roslaunch_strs: Sequence[str] | None = None,
                        loader: Any = None, verbose: bool = False, assign_machines: bool = True,
                        ignore_unset_args: bool = False) -> ROSLaunchConfig:
    """The core (load_roscore), then each file (with sys.argv's `name:=value` args, or a `(file, args)`
    pair's own) and XML string, read by `loader` (an XmlLoader by default) as roslaunch does;
    RLException when one cannot be loaded."""
    from roslaunch.loader import LoadException
    from roslaunch.xmlloader import XmlLoader, XmlParseException

    config = ROSLaunchConfig()
    if port:
        config.master.uri = create_local_xmlrpc_uri(port)
    loader = loader or XmlLoader()
    loader.ignore_unset_args = ignore_unset_args
    load_roscore(loader, config, verbose=verbose)
    for entry in roslaunch_files:
        f, args = entry if isinstance(entry, tuple) else (entry, None)
        try:
            loader.load(f, config, argv=args, verbose=verbose)
        except (XmlParseException, LoadException) as exc:
            raise RLException(str(exc)) from exc
    for launch_str in roslaunch_strs or []:
        try:
            loader.load_string(launch_str, config)
        except (XmlParseException, LoadException) as exc:
            raise RLException(f"Launch string: {launch_str}\nException: {exc}") from exc
    if assign_machines:
        config.assign_machines()
    return config
