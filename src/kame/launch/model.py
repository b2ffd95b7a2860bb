"""What a launch file declares, as plain data: parameters, nodes, tests, machines, setup commands.

The loader builds a `LaunchConfig`; the plan turns it into processes; nothing here does I/O.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from kame import names


@dataclass(frozen=True)
class Param:
    key: str
    value: Any  # bool, int, float, str, bytes (binfile), list or dict


@dataclass
class Node:
    """A <node> (or, with `test_name` set, a <test>)."""

    package: str
    type: str
    name: str
    namespace: str = "/"  # global, with a trailing slash
    machine_name: str | None = None
    args: str = ""
    respawn: bool = False
    respawn_delay: float = 0.0
    remap_args: list[tuple[str, str]] = field(default_factory=list)
    env_args: list[tuple[str, str]] = field(default_factory=list)
    output: str | None = None
    cwd: str | None = None
    launch_prefix: str | None = None
    required: bool = False
    filename: str = "<string>"
    line: int | None = None
    test_name: str | None = None
    time_limit: float = 60.0
    retry: int = 0

    @property
    def resolved_name(self) -> str:
        return names.ns_join(self.namespace, self.name)

    @property
    def is_test(self) -> bool:
        return self.test_name is not None


@dataclass(frozen=True)
class Machine:
    name: str
    address: str
    env_loader: str | None = None
    ssh_port: int = 22
    user: str | None = None
    password: str | None = None
    assignable: bool = True
    timeout: float | None = None


def node_problem(package: str, node_type: str, name: str | None, respawn: bool, required: bool,
                 output: str | None, cwd: str | None) -> str | None:
    """Why roslaunch refuses a node with these attributes (cwd already with `ros_home` as ROS_HOME),
    in its words and order; None when it takes it."""
    if respawn and required:
        return "respawn and required cannot both be set to true"
    if name and "/" in name:
        return "node name cannot contain a namespace"
    if not package.strip():
        return "package must be non-empty"
    if not node_type.strip():
        return "type must be non-empty"
    if output not in ("log", "screen", None):
        return "output must be one of 'log', 'screen'"
    if cwd not in ("ROS_HOME", "node", None):
        return "cwd must be one of 'ROS_HOME', 'node'"
    return None


LOCAL_ADDRESSES = frozenset({"localhost", "127.0.0.1", "::1", "0.0.0.0"})


@dataclass(frozen=True)
class Executable:
    """A setup command run before any node starts: `rosparam dump FILE NS` or `rosparam delete NS`."""

    command: str
    args: tuple[str, ...]


@dataclass
class LaunchConfig:
    params: dict[str, Param] = field(default_factory=dict)
    clear_params: list[str] = field(default_factory=list)
    nodes: list[Node] = field(default_factory=list)
    core_nodes: list[Node] = field(default_factory=list)
    tests: list[Node] = field(default_factory=list)
    machines: dict[str, Machine] = field(default_factory=dict)
    files: list[str] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)  # configuration warnings, printed after the summary
    executables: list[Executable] = field(default_factory=list)
    messages: list[str] = field(default_factory=list)  # -v lines ("Added parameter [/x]", ...)

    def add_param(self, param: Param, verbose: bool = False) -> None:
        for parent in _namespaces_of(param.key):
            if parent in self.params:
                self.errors.append(f"parameter [{param.key}] conflicts with parent parameter [{parent}]")
        self.params[param.key] = param
        if verbose:
            self.messages.append(f"Added parameter [{param.key}]")

    def add_node(self, node: Node, core: bool = False, verbose: bool = False) -> None:
        from kame.launch.errors import LaunchError

        resolved = node.resolved_name
        if any(n.resolved_name == resolved for n in (*self.nodes, *self.core_nodes)):
            raise LaunchError(
                f"roslaunch file contains multiple nodes named [{resolved}].\n"
                "Please check all <node> 'name' attributes to make sure they are unique.\n"
                "Also check that $(anon id) use different ids.", node.filename, node.line)
        kind = "core node" if core else "node"
        (self.core_nodes if core else self.nodes).append(node)
        if verbose:
            self.messages.append(f"Added {kind} of type [{node.package}/{node.type}] in namespace [{node.namespace}]")


def _namespaces_of(name: str) -> list[str]:
    """The parameter names that would hold `name` inside them: `/a/b/c` -> `/a`, `/a/b`."""
    parts = [p for p in name.split("/") if p]
    return ["/" + "/".join(parts[:i]) for i in range(1, len(parts))]
