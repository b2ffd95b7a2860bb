"""roslib.names: graph names (rosgraph.names) and package resource names (`pkg/Type`)."""

from __future__ import annotations

import re

from rosgraph.names import (
    ANYTYPE,
    GLOBALNS,
    PRIV_NAME,
    REMAP,
    SEP,
    anonymous_name,
    canonicalize_name,
    get_ros_namespace,
    is_global,
    is_legal_base_name,
    is_legal_name,
    is_private,
    isstring,
    load_mappings,
    make_caller_id,
    make_global_ns,
    namespace,
    ns_join,
    resolve_name,
)

# roslib's own patterns, which code matches names against directly
RESOURCE_NAME_LEGAL_CHARS_P = re.compile(r"^[A-Za-z][\w_\/]*$")
NAME_LEGAL_CHARS_P = re.compile(r"^[\~\/A-Za-z][\w_\/]*$")
BASE_NAME_LEGAL_CHARS_P = re.compile(r"^[A-Za-z][\w_]*$")
BASE_RESOURCE_NAME_LEGAL_CHARS_P = re.compile(r"^[A-Za-z][\w_]*$")

PRN_SEPARATOR = "/"
TYPE_SEPARATOR = PRN_SEPARATOR
_RESOURCE_NAME = re.compile(r"[A-Za-z][\w/]*\Z")
_RESOURCE_BASE_NAME = re.compile(r"[A-Za-z]\w*\Z")

__all__ = [
    "ANYTYPE",
    "BASE_NAME_LEGAL_CHARS_P",
    "BASE_RESOURCE_NAME_LEGAL_CHARS_P",
    "GLOBALNS",
    "NAME_LEGAL_CHARS_P",
    "PRIV_NAME",
    "PRN_SEPARATOR",
    "REMAP",
    "RESOURCE_NAME_LEGAL_CHARS_P",
    "SEP",
    "TYPE_SEPARATOR",
    "anonymous_name",
    "canonicalize_name",
    "get_ros_namespace",
    "is_global",
    "is_legal_base_name",
    "is_legal_name",
    "is_legal_resource_base_name",
    "is_legal_resource_name",
    "is_private",
    "isstring",
    "load_mappings",
    "make_caller_id",
    "make_global_ns",
    "namespace",
    "ns_join",
    "package_resource_name",
    "resolve_name",
    "resource_name",
    "resource_name_base",
    "resource_name_package",
]


def resource_name(res_pkg_name: str, name: str, my_pkg: str | None = None) -> str:
    """`pkg/name`, or just `name` when `pkg` is `my_pkg`."""
    return name if res_pkg_name == my_pkg else res_pkg_name + PRN_SEPARATOR + name


def resource_name_base(name: str) -> str:
    """`pkg/Type` -> `Type`."""
    return name[name.rfind(PRN_SEPARATOR) + 1:]


def resource_name_package(name: str) -> str | None:
    """`pkg/Type` -> `pkg`, `Type` -> None."""
    return name[:name.find(PRN_SEPARATOR)] if PRN_SEPARATOR in name else None


def package_resource_name(name: str) -> tuple[str, str]:
    """`pkg/Type` -> (`pkg`, `Type`), `Type` -> (``, `Type`); ValueError for more than one `/`."""
    if PRN_SEPARATOR not in name:
        return "", name
    parts = name.split(PRN_SEPARATOR)
    if len(parts) != 2:
        raise ValueError(f"invalid name [{name}]")
    return parts[0], parts[1]


def is_legal_resource_name(name: str | None) -> bool:
    """A letter, then letters, digits, `_` or `/`, and no `//` (`std_msgs/String`)."""
    return name is not None and _RESOURCE_NAME.match(name) is not None and "//" not in name


def is_legal_resource_base_name(name: str | None) -> bool:
    """A letter, then letters, digits or `_` (`String`)."""
    return name is not None and _RESOURCE_BASE_NAME.match(name) is not None
