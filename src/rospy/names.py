"""rospy.names: name resolution for this process's node, remapping tables and rospy's name
validators (over kame.client.core and rosgraph.names).

The command line's mappings are read from sys.argv until reload_mappings() gives others;
initialize_mappings() resolves them for a node name and makes them the ones resolve_name applies
(kame.client.core's table, which init_node fills).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from kame import environ
from kame import names as _names
from kame.client import core
from kame.client.errors import ROSException, ROSInitException
from rospy.impl.validators import ParameterInvalid

# rosgraph.names' functions, over kame.names here: importing the rosgraph package loads its master
# API (urllib.parse, ipaddress, random) into every rospy program
ANYTYPE = _names.ANY_TYPE
GLOBALNS = _names.GLOBAL_NS
REMAP = _names.REMAP
SEP = _names.SEP

__all__ = ["ANYTYPE", "GLOBALNS", "REMAP", "SEP", "SERVICE_ANYTYPE", "TOPIC_ANYTYPE", "ParameterInvalid",
           "ROSException", "ROSInitException", "canonicalize_name", "get_caller_id", "get_mappings", "get_name",
           "get_namespace", "get_resolved_mappings", "get_ros_namespace", "global_name", "initialize_mappings",
           "is_global", "is_private", "isstring", "load_mappings", "make_global_ns", "namespace", "ns_join",
           "reload_mappings", "remap_name", "resolve_name", "resolve_name_without_node_name", "scoped_name",
           "valid_name", "valid_name_validator_resolved", "valid_name_validator_unresolved"]

TOPIC_ANYTYPE = ANYTYPE  # a subscriber that takes whatever type its publishers send
SERVICE_ANYTYPE = ANYTYPE  # a service client without a fixed type

get_caller_id = core.get_caller_id
get_name = core.get_name
get_namespace = core.get_namespace



def isstring(s: object) -> bool:
    return isinstance(s, str)


def is_global(name: str | None) -> bool:
    return bool(name) and _names.is_global(name or "")


def is_private(name: str | None) -> bool:
    return bool(name) and _names.is_private(name or "")


def namespace(name: str) -> str:
    """The namespace of `name` with a trailing slash; ValueError for None, TypeError for a non-string."""
    if name is None:
        raise ValueError("name")
    if not isinstance(name, str):
        raise TypeError("name")
    return _names.namespace(name)


def ns_join(ns: str, name: str) -> str:
    return _names.ns_join(ns, name)


def make_global_ns(name: str) -> str:
    return _names.make_global_ns(name)


def get_ros_namespace(env: Mapping[str, str] | None = None, argv: Sequence[str] | None = None) -> str:
    """The `__ns:=` argument, else ROS_NAMESPACE, else `/`, as a global namespace (`/ns/`)."""
    for arg in sys.argv if argv is None else argv:
        if arg.startswith("__ns:="):
            return make_global_ns(arg[len("__ns:="):])
    return environ.namespace(os.environ if env is None else env)


def load_mappings(argv: Sequence[str]) -> dict[str, str]:
    """The name remappings among `argv` (`from:=to`), leaving out `_param:=value` assignments."""
    mappings: dict[str, str] = {}
    for arg in argv:
        if not _names.is_ros_arg(arg):
            continue
        parts = [part.strip() for part in arg.split(REMAP)]
        if len(parts) != 2:
            sys.stderr.write(f"ERROR: Invalid remapping argument '{arg}'\n")
            continue
        src, dst = parts
        if src and dst and not (len(src) > 1 and src[0] == "_" and src[1] != "_"):
            mappings[src] = dst
    return mappings


def _rosgraph_resolve(name: str, namespace_: str) -> str:
    """rosgraph.names.resolve_name without remappings."""
    if not name:
        return namespace(namespace_)
    return _names.resolve(name, namespace_)


_mappings: dict[str, str] | None = None  # reload_mappings' table; None: sys.argv's


def canonicalize_name(name: str) -> str:
    return _names.canonicalize(name)


def reload_mappings(argv: list[str]) -> None:
    """The remapping table is `argv`'s from now on."""
    global _mappings
    _mappings = load_mappings(argv)


def get_mappings() -> dict[str, str]:
    """The remappings on the command line, as written (`chatter` -> `/talk`, `__ns` -> `/n`),
    without the `_param:=` assignments."""
    return _mappings if _mappings is not None else load_mappings(sys.argv)


def initialize_mappings(node_name: str) -> None:
    """The command line's remappings resolved for `node_name` become the ones resolve_name
    applies (`__name`-like special keys kept as written)."""
    core.set_remappings({key if key.startswith("__") else _rosgraph_resolve(key, node_name):
                         value if key.startswith("__") else _rosgraph_resolve(value, node_name)
                         for key, value in get_mappings().items()})


def get_resolved_mappings() -> dict[str, str]:
    """The node's remappings with both sides resolved (empty before init_node)."""
    return core.get_remappings()


def resolve_name_without_node_name(name: str) -> str:
    """`name` resolved in this process's namespace before there is a node name: ValueError for a
    ~name, which needs one."""
    if is_private(name):
        raise ValueError("~name topics cannot be created before init_node() has been called")
    fake_caller_id = ns_join(get_namespace(), "node")
    fake_resolved = _rosgraph_resolve(name, fake_caller_id)
    for key, value in get_mappings().items():
        if _rosgraph_resolve(key, fake_caller_id) == fake_resolved:
            return _rosgraph_resolve(value, fake_caller_id)
    return fake_resolved


def resolve_name(name: str, caller_id: str | None = None) -> str:
    """`name` resolved for this node (or `caller_id`), remappings applied."""
    return core.resolve_name(str(name), caller_id or None)


def remap_name(name: str, caller_id: str | None = None, resolved: bool = True) -> str:
    """`name` remapped by the command line's mappings (resolved for `caller_id`), else as given."""
    mappings = get_mappings()
    if name in mappings:
        return _names.resolve(mappings[name], caller_id or core.get_caller_id())
    return name


def scoped_name(caller_id: str, name: str) -> str:
    """`name` relative to the namespace of the global `caller_id` (`/foo/node`, `/foo/bar` -> `bar`)."""
    if not is_global(caller_id):
        raise ROSException("caller_id must be global")
    return canonicalize_name(name)[len(namespace(caller_id)):]


def valid_name_validator_unresolved(param_name: str, param_value: Any, caller_id: str) -> str:
    """`param_value` if it is a non-empty name without `:` or space, else ParameterInvalid."""
    if not param_value or not isstring(param_value):
        raise ParameterInvalid(f"ERROR: parameter [{param_name}] must be a non-empty string")
    if ":" in param_value or " " in param_value:
        raise ParameterInvalid(f"ERROR: parameter [{param_name}] contains illegal chars")
    return str(param_value)


def valid_name_validator_resolved(param_name: str, param_value: Any, caller_id: str) -> str:
    """valid_name_validator_unresolved's name resolved for `caller_id` (no remapping)."""
    return _rosgraph_resolve(valid_name_validator_unresolved(param_name, param_value, caller_id), caller_id)


def valid_name(param_name: str, resolve: bool = True) -> Callable[[Any, str], str]:
    """A validator of a name parameter: non-empty, no `:` or space; resolved for the caller."""
    def validator(param_value: Any, caller_id: str) -> str:
        if resolve:
            return valid_name_validator_resolved(param_name, param_value, caller_id)
        return valid_name_validator_unresolved(param_name, param_value, caller_id)

    return validator


def global_name(param_name: str) -> Callable[[Any, str], str]:
    """A validator of a parameter that must be a global name."""
    def validator(param_value: Any, caller_id: str) -> str:
        if not param_value or not isstring(param_value):
            raise ParameterInvalid(f"ERROR: parameter [{param_name}] must be a non-empty string")
        if not is_global(param_value):
            raise ParameterInvalid(f"ERROR: parameter [{param_name}] must be a globally referenced name")
        return str(param_value)

    return validator
