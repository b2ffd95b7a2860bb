"""ParameterGenerator as dynamic_reconfigure's parameter_generator_catkin defines it, evaluated in process.

A .cfg file is a Python script that describes parameters and ends with
`exit(gen.generate(PACKAGE, node, name))`. catkin runs it at build time with four
arguments (the dynamic_reconfigure folder, the package's devel share, include and Python
folders) to write the Config module, the C++ header and the docs; kame writes the same
files when run so (kame.catkin.reconfigure_files' ParameterGenerator, which .cfg files
import), and when it evaluates the file on import
(kame.reconfigure.importer) generate() hands the description over instead.
The dictionaries have the keys and values catkin's generator makes, down to the double
limits' C++ spellings (replaced by infinities in the Python module) and the srcline and
srcfile of what upstream's own module created (its groups, and gen.add's parameters).
"""

from __future__ import annotations

import inspect
import math
import os
import re
from contextvars import ContextVar
from typing import Any

str_t = "str"
bool_t = "bool"
int_t = "int"
double_t = "double"

_PYTYPES: dict[str, Any] = {"str": str, "int": int, "double": float, "bool": bool}
_CTYPES = {"str": "std::string", "int": "int", "double": "double", "bool": "bool"}
_CCONSTTYPES = {"str": "const char * const", "int": "const int", "double": "const double", "bool": "const bool"}
CPP_INFINITY = "std::numeric_limits<double>::infinity()"
MINIMUM: dict[str, Any] = {"int": -0x80000000, "double": "-" + CPP_INFINITY, "str": "", "bool": False}
MAXIMUM: dict[str, Any] = {"int": 0x7FFFFFFF, "double": CPP_INFINITY, "str": "", "bool": True}
DEFAULT: dict[str, Any] = {"int": 0, "double": 0, "str": "", "bool": False}
# Where upstream's parameter_generator_catkin.py (1.7.3) makes the Default group, the other
# groups, and the parameters of gen.add: catkin's outputs name these lines.
UPSTREAM_FILE = "parameter_generator_catkin.py"
UPSTREAM_DEFAULT_GROUP_LINE = 246
UPSTREAM_GROUP_LINE = 124
UPSTREAM_ADD_LINE = 291
_NAME = re.compile(r"^[a-zA-Z][a-zA-Z0-9_]*$")

_collecting: ContextVar[list[GeneratedConfig] | None] = ContextVar("_collecting", default=None)


class GeneratedConfig:
    """What generate() produced: the package, node and config names, the tree and the constants."""

    def __init__(self, package: str, node: str, name: str, description: dict[str, Any],
                 constants: list[dict[str, Any]]) -> None:
        self.package = package
        self.node = node
        self.name = name
        self.description = description
        self.constants = constants


def collect_generated(results: list[GeneratedConfig] | None) -> None:
    """Make generate() in this context append to `results` (None: stop collecting)."""
    _collecting.set(results)


def _caller() -> tuple[int, str]:
    frame = inspect.currentframe()
    assert frame is not None and frame.f_back is not None and frame.f_back.f_back is not None
    caller = frame.f_back.f_back
    return caller.f_lineno, os.path.basename(caller.f_code.co_filename)


def _check_name(name: str) -> None:
    if not _NAME.match(name):
        raise ValueError(f"The name of field '{name}' does not follow the ROS naming conventions, "
                         "see http://wiki.ros.org/ROS/Patterns/Conventions")


def _check_description(description: str) -> None:
    if '"' in description or "'" in description:
        raise ValueError(f"quotes not allowed in description string `{description}`")


def _typed(name: str, drtype: str, field: str, value: Any) -> Any:
    pytype = _PYTYPES[drtype]
    if type(value) is not pytype and not (pytype is float and type(value) is int):
        raise TypeError(f"'{name}' has type {drtype}, but {field} is {value!r}")
    return pytype(value)


class Group:
    """A group of parameters (the root one is "Default"), as parameter_generator_catkin's Group."""

    def __init__(self, gen: ParameterGenerator, name: str, type: str, state: bool, id: int, parent: int) -> None:
        self.gen = gen
        self.name = name.replace(" ", "_")
        self.type = type
        self.state = state
        self.id = id
        self.parent = parent
        self.groups: list[Group] = []
        self.parameters: list[dict[str, Any]] = []
        self.srcline = UPSTREAM_DEFAULT_GROUP_LINE if id == 0 else UPSTREAM_GROUP_LINE
        self.srcfile = UPSTREAM_FILE

    def add_group(self, name: str, type: str = "", state: bool = True) -> Group:
        group = Group(self.gen, name, type, state, self.gen.next_group_id(), self.id)
        self.gen.groups[group.id] = group
        self.groups.append(group)
        return group

    def add(self, name: str, paramtype: str, level: int, description: str, default: Any = None,
            min: Any = None, max: Any = None, edit_method: str = "") -> None:
        self.add_from(_caller(), name, paramtype, level, description, default, min, max, edit_method)

    def add_from(self, source: tuple[int, str], name: str, paramtype: str, level: int, description: str,
                 default: Any = None, min: Any = None, max: Any = None, edit_method: str = "") -> None:
        """add(), recording `source` (line, file name) as where the parameter was added."""
        if paramtype not in _PYTYPES:
            raise ValueError(f"'{name}' has unknown type {paramtype!r}: use int_t, double_t, str_t or bool_t")
        if paramtype in (str_t, bool_t) and (max is not None or min is not None):
            raise ValueError(f"Max or min specified for {name}, which is of '{paramtype}' type")
        _check_name(name)
        srcline, srcfile = source
        param: dict[str, Any] = {"name": name, "type": paramtype, "default": default, "level": level,
                                 "description": description, "min": min, "max": max,
                                 "srcline": srcline, "srcfile": srcfile, "edit_method": edit_method,
                                 "ctype": _CTYPES[paramtype], "cconsttype": _CCONSTTYPES[paramtype]}
        for field, fallback in (("default", DEFAULT), ("max", MAXIMUM), ("min", MINIMUM)):
            value = param[field]
            param[field] = fallback[paramtype] if value is None else _typed(name, paramtype, field, value)
        self.parameters.append(param)

    def parents(self) -> list[str]:
        if self.id == 0:
            return [self.name]
        return [*self.gen.groups[self.parent].parents(), self.name]

    def to_dict(self) -> dict[str, Any]:
        parents = self.parents()
        return {
            "name": self.name, "type": self.type, "state": self.state, "cstate": "true" if self.state else "false",
            "id": self.id, "parent": self.parent, "parameters": self.parameters,
            "groups": [group.to_dict() for group in self.groups],
            "srcline": self.srcline, "srcfile": self.srcfile,
            "class": "::".join(p.upper() for p in parents),
            "parentclass": "::".join(p.upper() for p in parents[:-1]),
            "parentname": self.gen.groups[self.parent].name,
            "field": "::".join([p.upper() for p in parents[:-1]] + [parents[-1].lower()]),
            "upper": self.name.upper(),
            "lower": "groups" if self.id == 0 else self.name.lower(),
        }


class ParameterGenerator:
    """The object a .cfg file fills: add, add_group, const, enum, then generate(pkg, node, name)."""

    def __init__(self) -> None:
        self.groups: dict[int, Group] = {}
        self._last_id = 0
        self.group = Group(self, "Default", "", True, 0, 0)
        self.groups[0] = self.group
        self.constants: list[dict[str, Any]] = []

    def next_group_id(self) -> int:
        self._last_id += 1
        return self._last_id

    def const(self, name: str, type: str, value: Any, descr: str) -> dict[str, Any]:
        _check_description(descr)
        srcline, srcfile = _caller()
        constant = {"name": name, "type": type, "value": _typed(name, type, "value", value),
                    "srcline": srcline, "srcfile": srcfile, "description": descr,
                    "ctype": _CTYPES[type], "cconsttype": _CCONSTTYPES[type]}
        self.constants.append(constant)
        return constant

    def enum(self, constants: list[dict[str, Any]], description: str) -> str:
        if len({c["type"] for c in constants}) != 1:
            raise ValueError("Inconsistent types in enum!")
        _check_description(description)
        return repr({"enum": constants, "enum_description": description})

    def add(self, name: str, paramtype: str, level: int, description: str, default: Any = None,
            min: Any = None, max: Any = None, edit_method: str = "") -> None:
        self.group.add_from((UPSTREAM_ADD_LINE, UPSTREAM_FILE), name, paramtype, level, description, default,
                            min, max, edit_method)

    def add_group(self, name: str, type: str = "", state: bool = True) -> Group:
        return self.group.add_group(name, type=type, state=state)

    def generate(self, pkgname: str, nodename: str, name: str) -> int:
        results = _collecting.get()
        generated = GeneratedConfig(pkgname, nodename, name, self.group.to_dict(), self.constants)
        if results is not None:
            results.append(generated)
            return 0
        return self.write(generated)

    def write(self, generated: GeneratedConfig) -> int:
        """The .cfg run as a program: catkin's files are kame.catkin.reconfigure_files' (its
        ParameterGenerator, which .cfg files import, writes them when given catkin's arguments)."""
        print(f"{generated.name}Config for {generated.package}: kame loads it on `from {generated.package}.cfg "
              f"import {generated.name}Config`; no files are generated (catkin_make, or running this file with "
              "catkin's four arguments, writes them)")
        return 0


def flat_parameters(group: dict[str, Any]) -> list[dict[str, Any]]:
    """Every parameter of a description tree, depth first (dynamic_reconfigure.encoding.extract_params)."""
    params = list(group["parameters"])
    for child in group["groups"]:
        params.extend(flat_parameters(child))
    return params


def with_infinities(value: Any) -> Any:
    """A copy of a description with the C++ infinities as floats (upstream's replace_infinity for the Config module)."""
    if isinstance(value, dict):
        return {k: with_infinities(v) for k, v in value.items()}
    if isinstance(value, list):
        return [with_infinities(v) for v in value]
    if value == CPP_INFINITY:
        return math.inf
    if value == "-" + CPP_INFINITY:
        return -math.inf
    return value


def module_names(generated: GeneratedConfig) -> dict[str, Any]:
    """The names a catkin-generated <Name>Config module defines."""
    description = with_infinities(generated.description)
    params = flat_parameters(description)
    all_level = 0
    for param in params:
        all_level |= param["level"]
    names: dict[str, Any] = {
        "inf": math.inf,
        "config_description": description,
        "min": {p["name"]: p["min"] for p in params},
        "max": {p["name"]: p["max"] for p in params},
        "defaults": {p["name"]: p["default"] for p in params},
        "level": {p["name"]: p["level"] for p in params},
        "type": {p["name"]: p["type"] for p in params},
        "all_level": all_level,
    }
    for constant in generated.constants:
        names[f"{generated.name}_{constant['name']}"] = constant["value"]
    return names
