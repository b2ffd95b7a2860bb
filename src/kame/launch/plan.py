"""From a LaunchConfig to what roslaunch prints and starts: summary, listings, process specs.

Rules (roslaunch's config.summary, node_args, nodeprocess):
- A process is named `<ns/name>-<N>` (leading `/` dropped), N counting every process this
  launch starts; its logs are `<run dir>/<name with / as ->-N.log`, `...-stdout.log`.
- Its argv: launch-prefix words, the program, the args attribute split shell-like, `from:=to`
  remaps, `__name:=<name>`, `__log:=<log file>`. Its environment: ours, ROS_MASTER_URI,
  ROS_NAMESPACE for a namespaced node (unset at the root), then the <env>s in scope.
- Its working directory: ROS_HOME, or the program's folder with cwd="node".
- The summary lists parameter values `str()`-ed and cut to 20 characters (`<...>` when not
  printable), nodes grouped by namespace, all sorted.
"""

from __future__ import annotations

import json
import shlex
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict, dataclass, fields
from pathlib import Path
from typing import Any

import yaml

from kame.launch.errors import LaunchError
from kame.launch.model import LaunchConfig, Node


@dataclass(frozen=True)
class ProcessSpec:
    name: str  # "g1/talker-2"
    node: Node
    argv: tuple[str, ...]
    env: Mapping[str, str]
    cwd: str
    log_output: bool  # stdout to <log_name>-stdout.log (else to the terminal)
    log_name: str  # "g1-talker-2"

    @property
    def respawn(self) -> bool:
        return self.node.respawn

    @property
    def required(self) -> bool:
        return self.node.required


def process_name(node: Node, counter: int) -> str:
    return f"{node.resolved_name}-{counter}".lstrip("/")


def node_command(node: Node, program: Sequence[str]) -> list[str]:
    """The argv without `__log`: what `roslaunch --args` prints after the environment."""
    prefix = shlex.split(node.launch_prefix) if node.launch_prefix else []
    remaps = [f"{src}:={dst}" for src, dst in node.remap_args]
    return [*prefix, *program, *shlex.split(node.args), *remaps, f"__name:={node.name}"]


def node_env(node: Node, base: Mapping[str, str], master_uri: str) -> dict[str, str]:
    env = dict(base)
    env["ROS_MASTER_URI"] = master_uri
    env.pop("ROS_NAMESPACE", None)
    ns = node.namespace.rstrip("/")
    if ns:
        env["ROS_NAMESPACE"] = ns
    for name, value in node.env_args:
        env[name] = value
    return env


def plan_process(node: Node, counter: int, program: Sequence[str], base_env: Mapping[str, str], master_uri: str,
                 run_dir: Path, ros_home: Path, force_screen: bool = False, force_log: bool = False) -> ProcessSpec:
    name = process_name(node, counter)
    log_name = name.replace("/", "-")
    argv = [*node_command(node, program), f"__log:={run_dir / (log_name + '.log')}"]
    cwd = str(Path(program[-1]).parent) if node.cwd == "node" and program else str(ros_home)
    log_output = force_log or (node.output != "screen" and not force_screen)
    return ProcessSpec(name, node, tuple(argv), node_env(node, base_env, master_uri), cwd, log_output, log_name)


def args_line(node: Node, program: Sequence[str], base: Mapping[str, str], master_uri: str) -> str:
    """`roslaunch --args NODE`: the variables that differ from ours, then the command."""
    env = node_env(node, base, master_uri)
    changed = [f'{k}="{v}"' for k, v in env.items() if base.get(k) != v]
    return " ".join([*changed, *node_command(node, program)])


def _short(value: Any) -> str:
    text = value.decode("latin-1") if isinstance(value, bytes) else str(value)
    if len(text) > 20:
        text = text[:17] + "..."
    for i, char in enumerate(text):
        if not 32 <= ord(char) <= 126:
            text = text.rstrip()
            if i >= len(text):
                break
            return "<...>"
    return text


def summary(config: LaunchConfig, local: bool = True, is_local: Callable[[Node], bool] = lambda node: True) -> str:
    """The SUMMARY block roslaunch prints before starting anything (without the final newline).

    `local`: only this machine's nodes are run (no remote node, or --local): no MACHINES, and only
    the nodes `is_local` accepts."""
    out = "\nSUMMARY\n========"
    if config.clear_params:
        out += "\n\nCLEAR PARAMETERS\n" + "\n".join(sorted(f" * {p}" for p in config.clear_params))
    if config.params:
        out += "\n\nPARAMETERS\n" + "\n".join(sorted(f" * {k}: {_short(p.value)}" for k, p in config.params.items()))
    if not local:
        out += "\n\nMACHINES\n" + "\n".join(sorted(f" * {k}" for k in config.machines if k))
    out += "\n\nNODES\n"
    groups: dict[str, list[Node]] = {}
    for node in config.nodes:
        if local and not is_local(node):
            continue
        groups.setdefault(node.namespace, []).append(node)
    for ns in sorted(groups):
        out += f"  {ns}\n" + "\n".join(sorted(f"    {n.name} ({n.package}/{n.type})" for n in groups[ns])) + "\n"
    return out


def node_list(config: LaunchConfig) -> list[str]:
    return [n.resolved_name if not n.name.startswith("$") else n.name for n in (*config.nodes, *config.tests)]


def dump_params(config: LaunchConfig) -> str:
    """`roslaunch --dump-params`: every parameter as `/full/name: value`, YAML, sorted."""
    return yaml.safe_dump({str(k): p.value for k, p in config.params.items()}) + "\n"


def unify_clear_params(params: Sequence[str]) -> list[str]:
    """The namespaces to clear, those inside another left out."""
    ordered = sorted(set(params), key=len)
    kept: list[str] = []
    for p in ordered:
        if not any(p.startswith(k) for k in kept):
            kept.append(p)
    return kept


NODE_FIELDS = frozenset(f.name for f in fields(Node))


def nodes_to_json(nodes: Sequence[Node]) -> str:
    """The nodes a remote roslaunch child is to run, on one line (what its stdin first receives)."""
    return json.dumps([{**asdict(n), "machine_name": None} for n in nodes])


def nodes_from_json(text: str) -> list[Node]:
    """The nodes of `nodes_to_json`; LaunchError for anything else."""
    try:
        items = json.loads(text)
        if not isinstance(items, list):
            raise TypeError("not a list of nodes")
        nodes = []
        for item in items:
            if not isinstance(item, dict) or not set(item) <= NODE_FIELDS:
                raise TypeError(f"not a node: {item!r}")
            pairs = {k: [(str(a), str(b)) for a, b in item.get(k, [])] for k in ("remap_args", "env_args")}
            nodes.append(Node(**{**item, **pairs}))
        return nodes
    except (ValueError, TypeError) as exc:
        raise LaunchError(f"the parent roslaunch sent no list of nodes: {exc}") from None
