"""roslaunch.config: ROSLaunchConfig (what launch files declare, as roslaunch's objects) and
load_config_default, over kame's launch loader (kame.launch.loader through kame.cli.roslaunch).

`replay` hands a kame LaunchConfig to any object with roslaunch's add_* methods, as upstream's
loader fills a ROSLaunchConfig (or a test's stand-in for one).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

from kame.cli.roslaunch import load_config
from kame.launch.errors import LaunchError
from kame.launch.model import Executable, LaunchConfig
from kame.launch.model import Node as ModelNode
from kame.launch.remote import ENV_LOADER
from roslaunch.core import Machine, Master, Node, Param, RLException, Test, is_machine_local

__all__ = ["ROSLaunchConfig", "load_config_default", "replay"]


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
            m.env_loader = str(ENV_LOADER)
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
                              "remap_args": list(model.remap_args), "env_args": list(model.env_args),
                              "cwd": model.cwd, "launch_prefix": model.launch_prefix, "filename": model.filename}
    if model.test_name is not None:
        return Test(model.test_name, model.package, model.type, name=model.name, time_limit=model.time_limit,
                    retry=model.retry, **kwargs)
    return Node(model.package, model.type, name=model.name, respawn=model.respawn, respawn_delay=model.respawn_delay,
                output=model.output, required=model.required, **kwargs)


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
        ros_config.add_executable(exe)
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
    """The configuration of the core (rosout, /run_id's siblings) and of each file (or `(file, args)`)
    and XML string, as roslaunch loads them; RLException when one cannot be loaded."""
    files, argv = [], ["roslaunch"]
    for entry in roslaunch_files:
        if isinstance(entry, tuple):
            files.append(entry[0])
            argv += list(entry[1])
        else:
            files.append(entry)
    try:
        config, _ = load_config(files, argv, os.environ, strings=list(roslaunch_strs or []), verbose=verbose)
    except LaunchError as exc:
        raise RLException(str(exc)) from exc
    ros_config = ROSLaunchConfig()
    if port:
        ros_config.master = Master(uri=f"http://{ros_config.master.get_host()}:{port}/")
    replay(config, ros_config, verbose)
    if assign_machines:
        ros_config.assign_machines()
    return ros_config
