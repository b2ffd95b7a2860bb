"""roslaunch.node_args: a node's command line (create_local_process_args, get_node_args: what
`roslaunch --args` prints) and the node names of launch files (get_node_list, `--nodes`,
`--find-node`), as roslaunch's node_args, over kame's program lookup (kame.launch.runner.find_program)
and argv rules (kame.launch.plan.node_command).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping, Sequence
from typing import Any

import rosgraph
import rosgraph.names
from kame.launch import plan
from kame.launch.errors import LaunchError, PackageNotFound
from kame.launch.model import Node as ModelNode
from kame.launch.runner import find_program
from rosgraph.names import script_resolve_name
from roslaunch import substitution_args
from roslaunch.config import load_config_default
from roslaunch.core import RLException, local_machine, setup_env

__all__ = ["NodeParamsException", "RLException", "create_local_process_args", "get_node_args", "get_node_list",
           "load_config_default", "local_machine", "print_node_args", "print_node_filename", "print_node_list",
           "script_resolve_name", "setup_env"]


class NodeParamsException(Exception):
    """A node whose program cannot be found, or whose parameters are invalid."""


def _resolved_name(node: Any) -> str | None:
    if not node.name:
        return None
    return str(node.name) if node.name.startswith("$") else rosgraph.names.ns_join(node.namespace, node.name)


def get_node_list(config: Any) -> list[str]:
    """The resolved names of the nodes, then the tests, of a ROSLaunchConfig."""
    found = [_resolved_name(n) for n in config.nodes] + [_resolved_name(t) for t in config.tests]
    return [n for n in found if n]


def _config(roslaunch_files: Sequence[str]) -> Any:
    from roslaunch.xmlloader import XmlLoader

    return load_config_default(roslaunch_files, None, loader=XmlLoader(resolve_anon=False), verbose=False,
                               assign_machines=False)


def print_node_list(roslaunch_files: Sequence[str]) -> None:
    """`roslaunch --nodes`: the node names, one a line; exit status 1 on an error."""
    try:
        print("\n".join(get_node_list(_config(roslaunch_files))))
    except RLException as exc:
        print(str(exc), file=sys.stderr)
        sys.exit(1)


def print_node_args(node_name: str, roslaunch_files: Sequence[str]) -> None:
    """`roslaunch --args NODE`: the node's environment changes and command line."""
    try:
        print(" ".join(get_node_args(script_resolve_name("roslaunch", node_name), roslaunch_files)))
    except RLException as exc:
        print(str(exc), file=sys.stderr)
        sys.exit(1)


def _matching(config: Any, node_name: str, roslaunch_files: Sequence[str]) -> list[Any]:
    nodes = [n for n in (*config.nodes, *config.tests) if _resolved_name(n) == node_name]
    if len(nodes) > 1:
        raise RLException(f"ERROR: multiple nodes named [{node_name}] in [{', '.join(roslaunch_files)}].\n"
                          "Please fix the launch files as duplicate names are not allowed.")
    return nodes


def print_node_filename(node_name: str, roslaunch_files: Sequence[str]) -> None:
    """`roslaunch --find-node NODE`: the file that declares it."""
    try:
        node_name = script_resolve_name("roslaunch", node_name)
        nodes = _matching(_config(roslaunch_files), node_name, roslaunch_files)
        if not nodes:
            print(f"ERROR: cannot find node named [{node_name}]. Run \n\troslaunch --nodes <files>\n"
                  "to see list of node names.", file=sys.stderr)
        else:
            print(nodes[0].filename)
    except RLException as exc:
        print(str(exc), file=sys.stderr)
        sys.exit(1)


def get_node_args(node_name: str, roslaunch_files: Sequence[str]) -> list[str]:
    """`NAME="value"` for each variable the node's environment changes, then its command line."""
    config = _config(roslaunch_files)
    node_name = substitution_args.resolve_args(node_name, resolve_anon=False) or node_name
    if not node_name.startswith("$"):
        node_name = script_resolve_name("roslaunch", node_name)
    nodes = _matching(config, node_name, roslaunch_files)
    if not nodes:
        listed = "\n".join(f" * {x}" for x in get_node_list(config))
        raise RLException(f"ERROR: Cannot find node named [{node_name}] in [{', '.join(roslaunch_files)}].\n"
                          f"Node names are:\n{listed}")
    node = nodes[0]
    machine = local_machine()
    env = setup_env(node, machine, rosgraph.get_master_uri())
    changed = {k: v for k, v in env.items() if os.environ.get(k) != v}
    return [f'{k}="{v}"' for k, v in changed.items()] + create_local_process_args(node, machine)


def create_local_process_args(node: Any, machine: Any, env: Mapping[str, str] | None = None) -> list[str]:
    """The argv of `node`: launch-prefix, its program, its args ($(anon) resolved), remaps, `__name:=`.
    NodeParamsException when its package or program cannot be found."""
    if not node.name:
        raise ValueError("node name must be defined")
    context: dict[str, Any] = {}
    node.name = substitution_args.resolve_args(node.name, context=context, resolve_anon=True)
    args = substitution_args.resolve_args(node.args, context=context, resolve_anon=True) or ""
    try:
        program = find_program(node.package, node.type, os.environ if env is None else env)
    except PackageNotFound as exc:
        raise NodeParamsException(str(exc)) from None
    except LaunchError as exc:
        raise NodeParamsException(str(exc)) from None
    model = ModelNode(node.package, node.type, node.name, args=args, remap_args=list(node.remap_args),
                      launch_prefix=node.launch_prefix)
    return plan.node_command(model, program)
