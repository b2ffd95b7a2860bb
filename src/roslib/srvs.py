"""roslib.srvs: rosbuild's service specs (a request and a response MsgSpec), from .srv text or files."""

from __future__ import annotations

import os
import sys
from io import StringIO

from roslib import msgs as _msgs
from roslib import names as _names
from roslib import packages as _packages

__all__ = ["COMMENTCHAR", "EXT", "IODELIM", "SEP", "VERBOSE", "SrvSpec", "SrvSpecException", "get_pkg_srv_specs",
           "is_verbose", "list_srv_types", "load_from_file", "load_from_string", "set_verbose", "srv_file"]

EXT = ".srv"
SEP = "/"
IODELIM = "---"
COMMENTCHAR = _msgs.COMMENTCHAR
VERBOSE = False


def is_verbose() -> bool:
    """Whether loading says what it loads on stdout (set_verbose)."""
    return VERBOSE


def set_verbose(v: bool) -> None:
    global VERBOSE
    VERBOSE = v


class SrvSpecException(Exception):
    """A service definition that cannot be loaded."""


class SrvSpec:
    def __init__(self, request: _msgs.MsgSpec, response: _msgs.MsgSpec, text: str, full_name: str = "",
                 short_name: str = "", package: str = "") -> None:
        self.request = request
        self.response = response
        self.text = text
        self.full_name = full_name
        self.short_name = short_name
        self.package = package

    def __eq__(self, other: object) -> bool:
        return isinstance(other, SrvSpec) and (
            self.request, self.response, self.text, self.full_name, self.short_name, self.package) == (
            other.request, other.response, other.text, other.full_name, other.short_name, other.package)

    def __hash__(self) -> int:
        return hash((self.text, self.full_name))

    def __repr__(self) -> str:
        return f"SrvSpec[{self.request!r}, {self.response!r}]"


def list_srv_types(package: str, include_depends: bool) -> list[str]:
    """The service types (short names) `package` defines."""
    folder = os.path.dirname(srv_file(package, "x"))
    if not os.path.isdir(folder):
        return []
    return sorted(f[:-len(EXT)] for f in os.listdir(folder)
                  if f.endswith(EXT) and os.path.isfile(os.path.join(folder, f)))


def srv_file(package: str, type_: str) -> str:
    """The path of `package`'s srv/<type_>.srv (which need not exist)."""
    return _packages.resource_file(package, "srv", type_ + EXT)


def get_pkg_srv_specs(package: str) -> tuple[list[tuple[str, SrvSpec]], list[str]]:
    """(('pkg/Srv', spec) for each service of `package`, the types that failed to load)."""
    specs = []
    failures = []
    for type_ in list_srv_types(package, False):
        try:
            specs.append(load_from_file(srv_file(package, type_), package))
        except Exception:  # rosbuild reports each broken file and goes on
            failures.append(type_)
            sys.stderr.write(f"ERROR: unable to load {type_}\n")
    return specs, failures


def load_from_string(text: str, package_context: str = "", full_name: str = "", short_name: str = "") -> SrvSpec:
    """The spec of .srv `text`: its parts before and after `---`, comments stripped."""
    parts = (StringIO(), StringIO())
    part = 0
    for line in text.split("\n"):
        line = line.split(COMMENTCHAR)[0].strip()
        if line.startswith(IODELIM):  # lenient, as rosbuild: anything after the dashes is ignored
            part = 1
        else:
            parts[part].write(line + "\n")
    request = _msgs.load_from_string(parts[0].getvalue(), package_context, f"{full_name}Request",
                                     f"{short_name}Request")
    response = _msgs.load_from_string(parts[1].getvalue(), package_context, f"{full_name}Response",
                                      f"{short_name}Response")
    return SrvSpec(request, response, text, full_name, short_name, package_context)


def load_from_file(file_name: str, package_context: str = "") -> tuple[str, SrvSpec]:
    """('pkg/Srv', spec) of a .srv file; SrvSpecException for an illegal type name."""
    if VERBOSE:
        where = f" into namespace [{package_context}]" if package_context else ""
        sys.stdout.write(f"Load spec from {file_name}{where}\n")
    base_type = os.path.basename(file_name)[:-len(EXT)]
    package_context = package_context.rstrip(SEP)
    type_ = f"{package_context}{SEP}{base_type}" if package_context else base_type
    if not _names.is_legal_resource_name(type_):
        raise SrvSpecException(f"{file_name}: {type_} is not a legal service type name")
    with open(file_name) as f:
        return type_, load_from_string(f.read(), package_context, type_, base_type)
