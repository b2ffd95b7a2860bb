"""roslaunch.loader: what a launch loader (XmlLoader) builds on: LoaderContext (a scope's namespace,
remaps, ~params, env and args), Loader (params, <rosparam>, <env> and param values into a
ROSLaunchConfig), convert_value and the include-arg checks, with ROS's rules and wording.

<param> values are typed by kame's own rules (kame.launch.values), <rosparam> YAML is read as
the parameter server holds it (kame.param_yaml), and a command param runs as kame's roslaunch
runs it (kame.cli.roslaunch.run_command).
"""

from __future__ import annotations

import importlib
import os
import shlex
from collections.abc import Callable, Sequence
from copy import deepcopy
from types import ModuleType
from typing import Any

import yaml

from kame.cli.roslaunch import run_command
from kame.launch import values
from kame.param_yaml import ParamLoader, ParamValueError, check_shape
from rosgraph.names import PRIV_NAME, canonicalize_name, is_legal_name, load_mappings, make_global_ns, ns_join
from roslaunch.core import PHASE_SETUP, Param, RLException, RosbinExecutable

__all__ = ["PHASE_SETUP", "PRIV_NAME", "LoadException", "Loader", "LoaderContext", "Param", "RLException",
           "RosbinExecutable", "canonicalize_name", "convert_value", "deepcopy", "is_legal_name", "load_mappings",
           "load_sysargs_into_context", "make_global_ns", "ns_join", "post_process_include_args",
           "process_include_args", "rosparam"]

rosparam: ModuleType | None = None  # imported on the first <rosparam> load, as ROS's loader does


class LoadException(RLException):
    """Data that cannot be loaded as declared (an include's args, a missing file)."""


def convert_value(value: str, type_: str) -> Any:
    """`value` as `type_` (auto, str/string, int, double, bool/boolean, yaml); ValueError if it is not."""
    return values.convert_value(value, type_)


def process_include_args(context: LoaderContext) -> None:
    """Check that every arg declared for an include has a value, and make the include's args the
    context's own."""
    arg_dict = (context.include_resolve_dict or {}).get("arg", {})
    for arg in context.arg_names:
        if arg not in arg_dict:
            raise LoadException("include args must have declared values")
    context.args_passed = list(arg_dict)
    context.arg_names = []
    context.resolve_dict = context.include_resolve_dict or {}
    context.include_resolve_dict = None


def post_process_include_args(context: LoaderContext) -> None:
    """LoadException for an arg passed to an include that the included file does not declare."""
    bad = [a for a in context.args_passed if a not in context.arg_names]
    if bad:
        raise LoadException(f"unused args [{', '.join(bad)}] for include of [{context.filename}]")


def load_sysargs_into_context(context: LoaderContext, argv: Sequence[str]) -> None:
    """The `name:=value` arguments of `argv` as the context's args."""
    context.resolve_dict["arg"] = load_mappings(list(argv))


class LoaderContext:
    """A scope of a launch file: namespace, remaps, ~params, env and substitution args."""

    def __init__(self, ns: str | None, filename: str | None, parent: LoaderContext | None = None,
                 params: list[Param] | None = None, env_args: list[tuple[str, str]] | None = None,
                 resolve_dict: dict[str, Any] | None = None, include_resolve_dict: dict[str, Any] | None = None,
                 arg_names: list[str] | None = None) -> None:
        self.parent = parent
        self.ns = make_global_ns(ns or "/")
        self._remap_args: list[list[str]] = []
        self.params = params or []
        self.env_args = env_args or []
        self.filename = filename
        self.resolve_dict = resolve_dict or {}
        self.arg_names = arg_names or []
        self.include_resolve_dict = include_resolve_dict or None
        self.pass_all_args = False
        self.args_passed: list[str] = []

    def add_param(self, p: Param) -> None:
        """A ~param, for the nodes declared later in this scope (replacing one of the same key)."""
        self.params[:] = [m for m in self.params if m.key != p.key]
        self.params.append(p)

    def add_remap(self, remap: Sequence[str]) -> None:
        """A remap for later nodes in scope, replacing one from the same name."""
        pair = [canonicalize_name(x) for x in remap]
        if not pair[0] or not pair[1]:
            raise RLException("remap from/to attributes cannot be empty")
        if not is_legal_name(pair[0]):
            raise RLException(f"remap from [{pair[0]}] is not a valid ROS name")
        if not is_legal_name(pair[1]):
            raise RLException(f"remap to [{pair[1]}] is not a valid ROS name")
        self._remap_args = [r for r in self._remap_args if r[0] != pair[0]]
        self._remap_args.append(pair)

    def add_arg(self, name: str, default: str | None = None, value: str | None = None, doc: str | None = None) -> None:
        """Declare arg `name` here: `value` is fixed, `default` holds unless set from outside."""
        if name in self.arg_names:
            if not self.pass_all_args:
                raise LoadException(f"arg '{name}' has already been declared")
        else:
            self.arg_names.append(name)
        resolve_dict = self.resolve_dict if self.include_resolve_dict is None else self.include_resolve_dict
        arg_dict = resolve_dict.setdefault("arg", {})
        if value is not None:
            if name in arg_dict and not self.pass_all_args:
                raise LoadException(f"cannot override arg '{name}', which has already been set")
            arg_dict[name] = value
        elif default is not None and name not in arg_dict:
            arg_dict[name] = default
        arg_doc = resolve_dict.setdefault("arg_doc", {})
        if not value:
            arg_doc[name] = (doc, default)

    def remap_args(self) -> list[list[str]]:
        """The remaps in force: the parents' unless overridden here, then this scope's."""
        if self.parent is None:
            return self._remap_args[:]
        own = {r[0] for r in self._remap_args}
        return [r for r in self.parent.remap_args() if r[0] not in own] + self._remap_args

    def include_child(self, ns: str | None, filename: str) -> LoaderContext:
        """The scope of an <include> of `filename`: no args but those passed to it."""
        ctx = self.child(ns)
        ctx.arg_names = []
        ctx.filename = filename
        ctx.include_resolve_dict = {}
        return ctx

    def child(self, ns: str | None) -> LoaderContext:
        """A scope inside this one (a <group> or <node>), in sub-namespace `ns` if given."""
        if not ns:
            child_ns = self.ns
        elif ns[0] == "/" or ns == PRIV_NAME:
            child_ns = ns
        else:
            child_ns = ns_join(self.ns, ns)
        return LoaderContext(child_ns, self.filename, parent=self, params=self.params, env_args=self.env_args[:],
                             resolve_dict=deepcopy(self.resolve_dict), arg_names=self.arg_names[:],
                             include_resolve_dict=self.include_resolve_dict)


class Loader:
    """Checks and adds what a launch file declares to a ROSLaunchConfig (or anything with its add_* methods)."""

    def add_param(self, ros_config: Any, param_name: str, param_value: Any, verbose: bool = True) -> None:
        """One Param, or one per leaf of a dictionary value; ValueError if the name cannot hold it."""
        if not param_name:
            raise ValueError("no parameter name specified")
        if param_name == "/" and not isinstance(param_value, dict):
            raise ValueError("Cannot load non-dictionary types into global namespace '/'")
        if isinstance(param_value, dict):
            for key, value in param_value.items():
                self.add_param(ros_config, ns_join(param_name, key), value, verbose=verbose)
        else:
            ros_config.add_param(Param(param_name, param_value), verbose=verbose)

    def load_rosparam(self, context: LoaderContext, ros_config: Any, cmd: str, param: str | None, file_: str | None,
                      text: str, verbose: bool = True, subst_function: Callable[[str], str] | None = None) -> None:
        """A <rosparam>: `load` its YAML (file or text) as params, or `dump`/`delete` as a setup command."""
        if cmd not in ("load", "dump", "delete"):
            raise ValueError("command must be 'load', 'dump', or 'delete'")
        if file_ is not None:
            if cmd == "load" and not os.path.isfile(file_):
                raise ValueError(f"file does not exist [{file_}]")
            if cmd == "delete":
                raise ValueError("'file' attribute is invalid with 'delete' command.")
        full_param = ns_join(context.ns, param) if param else context.ns
        if cmd == "dump":
            ros_config.add_executable(RosbinExecutable("rosparam", (cmd, file_ or "", full_param), PHASE_SETUP))
            return
        if cmd == "delete":
            ros_config.add_executable(RosbinExecutable("rosparam", (cmd, full_param), PHASE_SETUP))
            return
        if file_:
            with open(file_) as f:
                text = f.read()
        if subst_function is not None:
            text = subst_function(text)
        global rosparam
        if rosparam is None:
            rosparam = importlib.import_module("rosparam")
        try:
            data = yaml.load(text, Loader=ParamLoader)
            check_shape(data)
        except (yaml.YAMLError, ParamValueError) as exc:
            if file_:
                raise ValueError(f"file {file_} contains invalid YAML:\n{exc}") from None
            raise ValueError(f"Error within YAML block:\n\t{exc}\n\nYAML is:\n{text}") from None
        if data is None:
            data = {}
        if not param and not isinstance(data, dict):
            raise ValueError("'param' attribute must be set for non-dictionary values")
        self.add_param(ros_config, full_param, data, verbose=verbose)

    def load_env(self, context: LoaderContext, ros_config: Any, name: str, value: str) -> None:
        """An <env>: set for the nodes later in the context."""
        if not name:
            raise ValueError("'name' attribute must be non-empty")
        context.env_args.append((name, value))

    def param_value(self, verbose: bool, name: str, ptype: str, value: str | None, textfile: str | None,
                    binfile: str | None, command: str | None) -> Any:
        """The value of a <param>, from its value, textfile, binfile (its bytes) or command."""
        if value is not None:
            return convert_value(value.strip(), ptype)
        if textfile is not None:
            with open(textfile) as f:
                return convert_value(f.read(), ptype)
        if binfile is not None:  # bytes: what kame's XML-RPC sends as base64 (ROS's loader wraps them in a Binary)
            with open(binfile, "rb") as b:
                return b.read()
        if command is not None:
            if verbose:
                print(f"... executing command param [{command}]")
            argv = shlex.split(command)
            try:
                status, out = run_command(argv)
            except FileNotFoundError:
                raise ValueError(f"Cannot load command parameter [{name}]: no such command [{argv}]") from None
            if status != 0:
                raise ValueError(f"Cannot load command parameter [{name}]: command [{argv}] returned with code "
                                 f"[{status}]")
            return convert_value(out, ptype)
        raise ValueError("unable to determine parameter value")
