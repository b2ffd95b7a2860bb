"""roslib.gentools: rosbuild's md5sums and full definition texts of roslib.msgs/roslib.srvs specs.

`get_dependencies` (or `get_file_dependencies`) gives the dict the other functions read:
'spec', 'package', 'deps' (the embedded types, depth first), 'uniquedeps' and, unless
compute_files=False, 'files' (each dependency's .msg path). Types are found on the package path
and registered in roslib.msgs as they are loaded.
"""

from __future__ import annotations

import hashlib
import sys
from io import StringIO
from typing import IO, Any

import rospkg
from roslib import msgs as _msgs
from roslib import names as _names
from roslib import srvs as _srvs
from roslib.msgs import MsgSpecException

__all__ = ["MsgSpecException", "compute_full_text", "compute_md5", "compute_md5_text", "compute_md5_v1",
           "compute_md5_v2", "get_dependencies", "get_file_dependencies"]

_header_type_name = "std_msgs/Header"


def _add_msgs_depends(rospack: rospkg.RosPack, spec: _msgs.MsgSpec, deps: list[str], package_context: str) -> None:
    """Append the types `spec` embeds to `deps`, depth first; KeyError for a type in a package
    `package_context` does not depend on."""
    valid_packages: list[str] | None = None
    for type_ in spec.types:
        type_ = str(_msgs.base_msg_type(type_))
        if _msgs.is_builtin(type_):
            continue
        type_package = _names.package_resource_name(type_)[0]
        if type_ == _msgs.HEADER:
            deps.append(_header_type_name)
        if _msgs.is_registered(type_):
            depspec = _msgs.get_registered(type_)
            if type_ != _msgs.HEADER:
                deps.append(type_ if "/" in type_ else f"{package_context}/{type_}")
        else:
            if valid_packages is None:
                valid_packages = ["", package_context]
                try:
                    valid_packages += rospack.get_depends(package_context, implicit=True)
                except rospkg.ResourceNotFound:
                    pass
            if type_package not in valid_packages:
                raise KeyError(type_)
            key, depspec = _msgs.load_by_type(type_, package_context)
            if type_ != _msgs.HEADER:
                deps.append(key)
            _msgs.register(key, depspec)
        _add_msgs_depends(rospack, depspec, deps, package_context)


def compute_md5_text(get_deps_dict: dict[str, Any], spec: _msgs.MsgSpec, rospack: rospkg.RosPack | None = None) -> str:
    """The text ROS hashes: constants first, then fields, each embedded type as its md5sum."""
    package = get_deps_dict["package"]
    compute_files = "files" in get_deps_dict
    buff = StringIO()
    for c in spec.constants:
        buff.write(f"{c.type} {c.name}={c.val_text}\n")
    for type_, name in zip(spec.types, spec.names, strict=True):
        base_type = str(_msgs.base_msg_type(type_))
        if _msgs.is_builtin(base_type):
            buff.write(f"{type_} {name}\n")
            continue
        if base_type == _msgs.HEADER:
            base_type = _header_type_name
        sub_package = _names.package_resource_name(base_type)[0] or package
        sub_spec = _msgs.get_registered(base_type, package)
        sub_deps = get_dependencies(sub_spec, sub_package, compute_files=compute_files, rospack=rospack)
        buff.write(f"{compute_md5(sub_deps, rospack)} {name}\n")
    return buff.getvalue().strip()


def compute_md5(get_deps_dict: dict[str, Any], rospack: rospkg.RosPack | None = None) -> str:
    """The md5sum of a message or service (a service: its request's text, then its response's)."""
    spec = get_deps_dict["spec"]
    md5 = hashlib.md5()
    if isinstance(spec, _msgs.MsgSpec):
        md5.update(compute_md5_text(get_deps_dict, spec, rospack=rospack).encode())
    elif isinstance(spec, _srvs.SrvSpec):
        md5.update(compute_md5_text(get_deps_dict, spec.request, rospack=rospack).encode())
        md5.update(compute_md5_text(get_deps_dict, spec.response, rospack=rospack).encode())
    else:
        raise Exception(f"[{spec}] is not a message or service")  # rosbuild's bare Exception
    return md5.hexdigest()


compute_md5_v2 = compute_md5


def compute_md5_v1(get_deps_dict: dict[str, Any]) -> str:
    """The md5sum ROS used before 0.6: of the texts of the spec and its dependencies."""
    md5 = hashlib.md5(get_deps_dict["spec"].text.encode())
    for dep in get_deps_dict["uniquedeps"]:
        md5.update(_msgs.get_registered(dep).text.encode())
    return md5.hexdigest()


def compute_full_text(get_deps_dict: dict[str, Any]) -> str:
    """The spec's text, then each dependency's after a line of 80 '=' and `MSG: pkg/Type`."""
    buff = StringIO()
    buff.write(get_deps_dict["spec"].text + "\n")
    for dep in get_deps_dict["uniquedeps"]:
        buff.write("=" * 80 + "\n")
        buff.write(f"MSG: {dep}\n")
        buff.write(_msgs.get_registered(dep).text + "\n")
    return buff.getvalue()[:-1]


def get_file_dependencies(f: str, stdout: IO[str] = sys.stdout, stderr: IO[str] = sys.stderr,
                          rospack: rospkg.RosPack | None = None) -> dict[str, Any]:
    """get_dependencies of the .msg or .srv file `f`, in the package that holds it."""
    package = rospkg.get_package_name(f) or ""
    spec: _msgs.MsgSpec | _srvs.SrvSpec
    if f.endswith(_msgs.EXT):
        spec = _msgs.load_from_file(f)[1]
    elif f.endswith(_srvs.EXT):
        spec = _srvs.load_from_file(f)[1]
    else:
        raise Exception(f"[{f}] does not appear to be a message or service")  # rosbuild's bare Exception
    return get_dependencies(spec, package, stdout=stdout, stderr=stderr, rospack=rospack)


def get_dependencies(spec: _msgs.MsgSpec | _srvs.SrvSpec, package: str, compute_files: bool = True,
                     stdout: IO[str] = sys.stdout, stderr: IO[str] = sys.stderr,
                     rospack: rospkg.RosPack | None = None) -> dict[str, Any]:
    """The dependencies of `spec` in `package` (see the module's docstring)."""
    _msgs._init()
    deps: list[str] = []
    try:
        rospack = rospack or rospkg.RosPack()
        if isinstance(spec, _msgs.MsgSpec):
            _add_msgs_depends(rospack, spec, deps, package)
        elif isinstance(spec, _srvs.SrvSpec):
            _add_msgs_depends(rospack, spec.request, deps, package)
            _add_msgs_depends(rospack, spec.response, deps, package)
        else:
            raise MsgSpecException("spec does not appear to be a message or service")
    except KeyError as exc:
        raise MsgSpecException(f"Cannot load type {exc}.  Perhaps the package is missing a dependency.") from None
    uniquedeps = list(dict.fromkeys(deps))
    answer: dict[str, Any] = {"deps": deps, "spec": spec, "package": package, "uniquedeps": uniquedeps}
    if compute_files:
        files = {}
        for dep in set(deps):
            dep_package, type_ = _names.package_resource_name(dep)
            files[dep] = _msgs.msg_file(dep_package or package, type_)
        answer = {"files": files, **answer}
    return answer
