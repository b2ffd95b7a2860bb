"""genmsg.names: package resource names ('std_msgs/String') split, joined and checked."""

from __future__ import annotations

import re

__all__ = ["BASE_RESOURCE_NAME_LEGAL_CHARS_P", "PRN_SEPARATOR", "RESOURCE_NAME_LEGAL_CHARS_P",
           "is_legal_resource_base_name", "is_legal_resource_name", "normalize_package_context",
           "package_resource_name", "resource_name", "resource_name_base", "resource_name_package"]

PRN_SEPARATOR = "/"
RESOURCE_NAME_LEGAL_CHARS_P = re.compile(r"^[A-Za-z][\w_\/]*$")
BASE_RESOURCE_NAME_LEGAL_CHARS_P = re.compile(r"^[A-Za-z][\w_]*$")


def normalize_package_context(package_context: str) -> str:
    """The context stripped of whitespace and trailing separators."""
    return package_context.strip().rstrip(PRN_SEPARATOR)


def resource_name(res_pkg_name: str, name: str, my_pkg: str | None = None) -> str:
    """'pkg/name', or just 'name' when it is in `my_pkg`."""
    return name if res_pkg_name == my_pkg else res_pkg_name + PRN_SEPARATOR + name


def resource_name_base(name: str) -> str:
    """'pkg/typeName' -> 'typeName'."""
    return name[name.rfind(PRN_SEPARATOR) + 1:]


def resource_name_package(name: str) -> str | None:
    """'pkg/typeName' -> 'pkg'; None for a name without a package."""
    return name[:name.find(PRN_SEPARATOR)] if PRN_SEPARATOR in name else None


def package_resource_name(name: str) -> tuple[str, str]:
    """'std_msgs/String' -> ('std_msgs', 'String'), 'String' -> ('', 'String'); ValueError for
    more than one separator."""
    if PRN_SEPARATOR not in name:
        return "", name
    parts = name.split(PRN_SEPARATOR)
    if len(parts) != 2:
        raise ValueError(f"invalid name [{name}]")
    return parts[0], parts[1]


def is_legal_resource_name(name: str | None) -> bool:
    """A letter, then letters, digits, underscores or single slashes."""
    if name is None:
        return False
    m = RESOURCE_NAME_LEGAL_CHARS_P.match(name)
    return m is not None and m.group(0) == name and "//" not in name


def is_legal_resource_base_name(name: str | None) -> bool:
    """A name without a package: a letter, then letters, digits or underscores."""
    if name is None:
        return False
    m = BASE_RESOURCE_NAME_LEGAL_CHARS_P.match(name)
    return m is not None and m.group(0) == name
