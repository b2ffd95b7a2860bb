"""rospy.names: name resolution for this process's node, remapping tables and rospy's name
validators (over kame.client.core and rosgraph.names)."""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import Any

from kame import names as _names
from kame.client import core
from kame.client.errors import ROSException
from rosgraph.names import (
    ANYTYPE,
    GLOBALNS,
    REMAP,
    SEP,
    get_ros_namespace,
    is_global,
    is_private,
    load_mappings,
    make_global_ns,
    namespace,
    ns_join,
)
from rospy.impl.validators import ParameterInvalid

__all__ = ["ANYTYPE", "GLOBALNS", "REMAP", "SEP", "ParameterInvalid", "canonicalize_name", "get_caller_id",
           "get_mappings", "get_name", "get_namespace", "get_resolved_mappings", "get_ros_namespace",
           "global_name", "is_global", "is_private", "load_mappings", "make_global_ns", "namespace", "ns_join",
           "remap_name", "resolve_name", "scoped_name", "valid_name"]

get_caller_id = core.get_caller_id
get_name = core.get_name
get_namespace = core.get_namespace


def canonicalize_name(name: str) -> str:
    return _names.canonicalize(name)


def get_mappings() -> dict[str, str]:
    """The remappings on the command line, as written (`chatter` -> `/talk`, `__ns` -> `/n`),
    without the `_param:=` assignments."""
    return load_mappings(sys.argv)


def get_resolved_mappings() -> dict[str, str]:
    """The node's remappings with both sides resolved (empty before init_node)."""
    return core.get_remappings()


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


def _checked(param_name: str, param_value: Any) -> str:
    if not param_value or not isinstance(param_value, str):
        raise ParameterInvalid(f"ERROR: parameter [{param_name}] must be a non-empty string")
    if ":" in param_value or " " in param_value:
        raise ParameterInvalid(f"ERROR: parameter [{param_name}] contains illegal chars")
    return param_value


def valid_name(param_name: str, resolve: bool = True) -> Callable[[Any, str], str]:
    """A validator of a name parameter: non-empty, no `:` or space; resolved for the caller."""
    def validator(param_value: Any, caller_id: str) -> str:
        value = _checked(param_name, param_value)
        return _names.resolve(value, caller_id) if resolve else value

    return validator


def global_name(param_name: str) -> Callable[[Any, str], str]:
    """A validator of a parameter that must be a global name."""
    def validator(param_value: Any, caller_id: str) -> str:
        if not param_value or not isinstance(param_value, str):
            raise ParameterInvalid(f"ERROR: parameter [{param_name}] must be a non-empty string")
        if not is_global(param_value):
            raise ParameterInvalid(f"ERROR: parameter [{param_name}] must be a globally referenced name")
        return param_value

    return validator
