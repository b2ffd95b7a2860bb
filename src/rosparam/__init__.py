"""rosparam as a library: load YAML files and read and write parameters, as ROS code calls it
(`rosparam.upload_params(ns, rosparam.load_file(path)[0][0])`). The `rosparam` command is
kame.cli.rosparam; both read YAML with ROS's rules (kame.param_yaml: !radians, !degrees,
`_ns`) and set dicts leaf by leaf, so they merge into what is there.
"""

from __future__ import annotations

import base64
import os
import re
import sys
from collections.abc import Sequence
from optparse import OptionParser
from typing import Any

import yaml

import rosgraph
from kame import names, param_yaml
from kame.cli import rosparam as _command

__all__ = ["GLOBALNS", "NAME", "NS", "Binary", "OptionParser", "RosParamException", "RosParamIOException",
           "construct_angle_degrees", "construct_angle_radians", "construct_yaml_binary", "delete_param", "dump_params",
           "get_param", "get_param_server", "get_ros_namespace", "list_params", "load_file", "load_str",
           "make_caller_id", "make_global_ns", "ns_join", "pattern", "print_params", "represent_foo",
           "represent_xml_binary", "script_resolve_name", "set_param", "set_param_raw", "upload_params", "yamlmain"]

NS_KEY = "_ns"


class RosParamException(Exception):
    """A bad parameter file or value."""


class RosParamIOException(RosParamException):
    """The master could not be reached."""


def get_param_server() -> rosgraph.Master:
    return rosgraph.Master(f"/rosparam-{os.getpid()}")


def load_str(text: str, filename: str, default_namespace: str | None = None,
             verbose: bool = False) -> list[tuple[Any, str]]:
    """Each YAML document of `text` with the namespace it goes to: `default_namespace` (this
    process's namespace when None), joined with the document's `_ns` key if it has one."""
    namespace = default_namespace or rosgraph.names.get_ros_namespace()
    try:
        documents = param_yaml.load_all(text)
    except param_yaml.ParamValueError as exc:
        raise RosParamException(f"error loading yaml in {filename}: {exc}") from None
    loaded: list[tuple[Any, str]] = []
    for document in documents:
        doc = {} if document is None else document
        ns = namespace
        if isinstance(doc, dict) and NS_KEY in doc:
            ns = names.ns_join(namespace, str(doc.pop(NS_KEY)))
            if verbose:
                print(f"reading parameters into namespace [{ns}]")
        loaded.append((doc, ns))
    return loaded


def load_file(filename: str, default_namespace: str | None = None, verbose: bool = False) -> list[tuple[Any, str]]:
    """load_str on the file's text; RosParamException when the file does not exist."""
    if not os.path.isfile(filename):
        raise RosParamException(f"file [{filename}] does not exist")
    if verbose:
        print(f"reading parameters from [{filename}]")
    with open(filename, encoding="utf-8") as f:
        return load_str(f.read(), filename, default_namespace, verbose)


def _call(method: str, *args: Any) -> Any:
    try:
        return getattr(get_param_server(), method)(*args)
    except OSError:
        raise RosParamIOException("Unable to communicate with master!") from None


def get_param(param: str) -> Any:
    """The parameter's value (a dict for a namespace); rosgraph.MasterError when it is not set."""
    return _call("getParam", param)


def set_param_raw(param: str, value: Any, verbose: bool = False) -> None:
    """Set `value` at `param`; a dict is set key by key (merging into what is there)."""
    try:
        param_yaml.check(param, value)
    except param_yaml.ParamValueError as exc:
        raise RosParamException(str(exc)) from None
    for key, leaf in param_yaml.leaves(param, value):
        _call("setParam", key, leaf)
        if verbose:
            print(f"set parameter [{key}] to [{leaf}]")


def set_param(param: str, value: str, verbose: bool = False) -> None:
    """Set the parameter to the YAML text `value`."""
    try:
        parsed = param_yaml.load(value)
    except param_yaml.ParamValueError as exc:
        raise RosParamException(str(exc)) from None
    set_param_raw(param, parsed, verbose)


def upload_params(ns: str, values: Any, verbose: bool = False) -> None:
    """Set `values` (what load_file read) under namespace `ns`."""
    if ns == "/" and not isinstance(values, dict):
        raise RosParamException("global / can only be set to a dictionary")
    if verbose:
        print("\n".join(param_yaml.verbose_lines(values, ns)))
    set_param_raw(ns, values)


def delete_param(param: str, verbose: bool = False) -> None:
    """Delete the parameter (or namespace); RosParamException when it is not set."""
    try:
        _call("deleteParam", param)
    except rosgraph.MasterException:
        raise RosParamException(f"parameter [{param}] is not set") from None
    if verbose:
        print(f"deleted parameter [{param}]")


def list_params(ns: str) -> list[str]:
    """The parameter names under namespace `ns`, sorted."""
    prefix = names.make_global_ns(ns)
    found = [str(name) for name in _call("getParamNames")]
    return sorted(name for name in found if ns == "/" or name == ns.rstrip("/") or name.startswith(prefix))


# ---------------------------------------------------------------- rosparam's YAML hooks and command

NAME = "rosparam"
NS = NS_KEY


class Binary(bytes):
    """Binary data as the parameter server holds it (xmlrpc.client's Binary: the bytes are in
    `data`); bytes itself, so kame's XML-RPC client sends it as base64."""

    @property
    def data(self) -> bytes:
        return bytes(self)

GLOBALNS = rosgraph.names.GLOBALNS
get_ros_namespace = rosgraph.names.get_ros_namespace
make_caller_id = rosgraph.names.make_caller_id
make_global_ns = rosgraph.names.make_global_ns
ns_join = rosgraph.names.ns_join
script_resolve_name = rosgraph.names.script_resolve_name
pattern = re.compile(r"^rad\([^\)]*\)$")  # rosparam's last-bound pattern: `rad(...)`, the implicit !radians


def represent_xml_binary(loader: Any, data: Binary) -> Any:
    """YAML for an XML-RPC Binary: base64, as rosparam dumps it. rosparam registers its hooks with
    pyyaml as it is imported; kame's rosparam reads YAML with kame.param_yaml and leaves pyyaml as is."""
    return loader.represent_scalar("tag:yaml.org,2002:binary", base64.b64encode(data.data), style="|")


def represent_foo(loader: Any, data: Any) -> Any:
    return loader.represent_scalar("#", data)


def construct_yaml_binary(loader: Any, node: Any) -> Binary:
    """YAML binary data as an XML-RPC Binary, as the parameter server stores it."""
    return Binary(loader.construct_yaml_binary(node))


def construct_angle_radians(loader: Any, node: Any) -> float:
    """`rad(pi/2)` or `pi/2` in radians (arithmetic and pi only, not Python as rosparam's eval)."""
    try:
        return param_yaml.radians(str(loader.construct_scalar(node)))
    except param_yaml.ParamValueError as exc:
        raise RosParamException(str(exc)) from None


def construct_angle_degrees(loader: Any, node: Any) -> float:
    """`deg(90)` or `90` in radians."""
    try:
        return param_yaml.degrees(str(loader.construct_scalar(node)))
    except param_yaml.ParamValueError as exc:
        raise RosParamException(str(exc)) from None


def print_params(params: Any, ns: str) -> None:
    """Each leaf of `params` as `ns/key=value` (a value that is no dict: as it is)."""
    if isinstance(params, dict):
        for key, value in params.items():
            if isinstance(value, dict):
                print_params(value, ns_join(ns, key))
            else:
                print(f"{ns_join(ns, key)}={value}")
    else:
        print(params)


def dump_params(filename: str | None, param: str, verbose: bool = False) -> None:
    """Write the parameter (or namespace) `param` as YAML to `filename` (stdout when empty)."""
    tree = get_param(param)
    if verbose:
        print_params(tree, param)
    if not filename:
        yaml.dump(tree, sys.stdout)
        return
    with open(filename, "w") as f:
        yaml.dump(tree, f)


def yamlmain(argv: Sequence[str] | None = None) -> None:
    """The rosparam command on `argv` (sys.argv: the program, then the command); ends the process."""
    sys.exit(_command.main(None if argv is None else list(argv)[1:]))
