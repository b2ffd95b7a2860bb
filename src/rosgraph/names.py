"""rosgraph.names: ROS graph resource names (kame.names, with rosgraph's function names)."""

from __future__ import annotations

import os
import random
import re
import sys
from collections.abc import Mapping, Sequence

from kame import names as _names
from kame.net.interfaces import hostname

from .rosenv import ROS_NAMESPACE

MSG_EXT = ".msg"
SRV_EXT = ".srv"
SEP = _names.SEP
GLOBALNS = _names.GLOBAL_NS
PRIV_NAME = _names.PRIVATE_PREFIX
REMAP = _names.REMAP
ANYTYPE = _names.ANY_TYPE
# rosgraph's own patterns, which code matches names against directly
NAME_LEGAL_CHARS_P = re.compile(r"^[\~\/A-Za-z][\w\/]*$")
BASE_NAME_LEGAL_CHARS_P = re.compile(r"^[A-Za-z][\w]*$")
REMAP_PATTERN = re.compile(r"^([\~\/A-Za-z]|_|__)[\w\/]*" + REMAP + ".*")

__all__ = [
    "ANYTYPE",
    "BASE_NAME_LEGAL_CHARS_P",
    "GLOBALNS",
    "MSG_EXT",
    "NAME_LEGAL_CHARS_P",
    "PRIV_NAME",
    "REMAP",
    "REMAP_PATTERN",
    "SEP",
    "SRV_EXT",
    "anonymous_name",
    "canonicalize_name",
    "get_ros_namespace",
    "is_global",
    "is_legal_base_name",
    "is_legal_name",
    "is_legal_remap",
    "is_private",
    "isstring",
    "load_mappings",
    "make_caller_id",
    "make_global_ns",
    "namespace",
    "ns_join",
    "resolve_name",
    "script_resolve_name",
]


def isstring(s: object) -> bool:
    return isinstance(s, str)


def get_ros_namespace(env: Mapping[str, str] | None = None, argv: Sequence[str] | None = None) -> str:
    """The `__ns:=` argument, else ROS_NAMESPACE, else `/`, as a global namespace (`/ns/`)."""
    for arg in sys.argv if argv is None else argv:
        if arg.startswith("__ns:="):
            return make_global_ns(arg[len("__ns:="):])
    env = os.environ if env is None else env
    return make_global_ns(env.get(ROS_NAMESPACE, GLOBALNS))


def make_caller_id(name: str) -> str:
    """`name` in this process's namespace, made global with a trailing slash."""
    return make_global_ns(ns_join(get_ros_namespace(), name))


def make_global_ns(name: str) -> str:
    return _names.make_global_ns(name)


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


def load_mappings(argv: Sequence[str]) -> dict[str, str]:
    """The name remappings among `argv` (`from:=to`), leaving out `_param:=value` assignments."""
    mappings: dict[str, str] = {}
    for arg in argv:
        if not is_legal_remap(arg):
            continue
        parts = [part.strip() for part in arg.split(REMAP)]
        if len(parts) != 2:
            sys.stderr.write(f"ERROR: Invalid remapping argument '{arg}'\n")
            continue
        src, dst = parts
        if src and dst and not (len(src) > 1 and src[0] == "_" and src[1] != "_"):
            mappings[src] = dst
    return mappings


def is_legal_name(name: str | None) -> bool:
    return name is not None and _names.is_legal_name(name)


def is_legal_base_name(name: str | None) -> bool:
    return name is not None and _names.is_legal_base_name(name)


def is_legal_remap(arg: str | None) -> bool:
    return arg is not None and _names.is_ros_arg(arg)


def canonicalize_name(name: str) -> str:
    return _names.canonicalize(name)


def resolve_name(name: str, namespace_: str, remappings: Mapping[str, str] | None = None) -> str:
    """`name` resolved in `namespace_` (a node's full name for ~private names), then remapped."""
    if not name:
        return namespace(namespace_)
    return _names.resolve(name, namespace_, remappings)


def script_resolve_name(script_name: str, name: str) -> str:
    """`name` resolved for a script (ROS_NAMESPACE; no remappings)."""
    if not name:
        return get_ros_namespace()
    if is_global(name):
        return name
    if is_private(name):
        return ns_join(make_caller_id(script_name), name[1:])
    return get_ros_namespace() + name


def anonymous_name(id: str) -> str:
    """`id` made unique: host name, pid and a random number appended, with `.`, `-`, `:` as `_`."""
    name = f"{id}_{hostname()}_{os.getpid()}_{random.randint(0, sys.maxsize)}"
    return name.replace(".", "_").replace("-", "_").replace(":", "_")
