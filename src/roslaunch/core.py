"""roslaunch.core: the Node a script launches, and RLException."""

from __future__ import annotations

from kame import names
from kame.launch.errors import LaunchError
from kame.launch.model import Node as ModelNode

RLException = LaunchError


class Node:
    """A node to launch, as roslaunch.core.Node takes it."""

    def __init__(self, package: str, node_type: str, name: str | None = None, namespace: str = "/",
                 machine_name: str | None = None, args: str = "", respawn: bool = False, respawn_delay: float = 0.0,
                 remap_args: list[tuple[str, str]] | None = None, env_args: list[tuple[str, str]] | None = None,
                 output: str | None = None, cwd: str | None = None, launch_prefix: str | None = None,
                 required: bool = False, filename: str = "<unknown>") -> None:
        self.package = package
        self.type = node_type
        self.name = name
        self.namespace = names.make_global_ns(namespace or "/")
        self.machine_name = machine_name
        self.args = args
        self.respawn = respawn
        self.respawn_delay = respawn_delay
        self.remap_args = list(remap_args or [])
        self.env_args = list(env_args or [])
        self.output = output
        self.cwd = cwd
        self.launch_prefix = launch_prefix
        self.required = required
        self.filename = filename

    def to_model(self, default_name: str) -> ModelNode:
        return ModelNode(self.package, self.type, self.name or default_name, namespace=self.namespace,
                         machine_name=self.machine_name, args=self.args, respawn=self.respawn,
                         respawn_delay=self.respawn_delay, remap_args=list(self.remap_args),
                         env_args=list(self.env_args), output=self.output, cwd=self.cwd,
                         launch_prefix=self.launch_prefix, required=self.required, filename=self.filename)
