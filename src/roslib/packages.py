"""roslib.packages: package folders and the files in them (rospkg's search path, kame's rules
for finding a package's programs)."""

from __future__ import annotations

import os
import stat
from collections.abc import Callable, Mapping
from pathlib import Path
from subprocess import PIPE, Popen  # roslib.packages' own imports, which code reaches for
from typing import Any

import rospkg
from kame.catkin.executables import find_node as _find_node
from kame.catkin.find_in_workspaces import find_in_workspaces as catkin_find
from kame.msg.catalog import Package
from rospkg.environment import ROS_PACKAGE_PATH, ROS_ROOT

MANIFEST_FILE = "manifest.xml"
PACKAGE_FILE = "package.xml"
SRC_DIR = "src"

__all__ = [
    "MANIFEST_FILE",
    "PACKAGE_FILE",
    "PIPE",
    "ROS_PACKAGE_PATH",
    "ROS_ROOT",
    "SRC_DIR",
    "InvalidROSPkgException",
    "MultipleNodesException",
    "Popen",
    "ROSPkgException",
    "catkin_find",
    "find_node",
    "find_resource",
    "get_dir_pkg",
    "get_pkg_dir",
    "get_pkg_subdir",
    "resource_file",
]


class ROSPkgException(Exception):
    """Base class of roslib.packages' errors."""


class InvalidROSPkgException(ROSPkgException):
    """A package that cannot be found or is malformed."""


class MultipleNodesException(ROSPkgException):
    """More than one program matches a node type."""


def get_dir_pkg(d: str) -> tuple[str | None, str | None]:
    """(folder, name) of the nearest folder at or above `d` with a manifest, else (None, None)."""
    def has_manifest(folder: str) -> bool:
        return any(os.path.exists(os.path.join(folder, f)) for f in (MANIFEST_FILE, PACKAGE_FILE))

    parent = os.path.dirname(os.path.realpath(d))
    while not has_manifest(d) and parent != d:
        d = parent
        parent = os.path.dirname(d)
    if has_manifest(d):
        return d, os.path.basename(os.path.abspath(d))
    return None, None


def _rospack(ros_root: str | None = None, ros_package_path: str | None = None) -> rospkg.RosPack:
    env = dict(os.environ)
    if ros_root is not None:
        env[ROS_ROOT] = ros_root
    if ros_package_path is not None:
        env[ROS_PACKAGE_PATH] = ros_package_path
    return rospkg.RosPack.get_instance(rospkg.get_ros_paths(env))  # type: ignore[no-any-return]


def get_pkg_dir(package: str, required: bool = True, ros_root: str | None = None,
                ros_package_path: str | None = None) -> str | None:
    """The folder of `package`; InvalidROSPkgException (or None when not `required`) if none."""
    try:
        return os.path.normpath(_rospack(ros_root, ros_package_path).get_path(package))
    except rospkg.ResourceNotFound as exc:
        if not required:
            return None
        roots = ros_root or os.environ.get(ROS_ROOT)
        path = ros_package_path or os.environ.get(ROS_PACKAGE_PATH)
        raise InvalidROSPkgException(f"Cannot locate installation of package {package}: [rospack] Error: "
                                     f"package '{package}' not found. ROS_ROOT[{roots}] ROS_PACKAGE_PATH[{path}]"
                                     ) from exc


def get_pkg_subdir(package: str, subdir: str, required: bool = True, env: Mapping[str, str] | None = None
                   ) -> str | None:
    """`package`'s folder `subdir`, created when `required` and missing; None if not `required`
    and it cannot be had."""
    env = os.environ if env is None else env
    package_dir = get_pkg_dir(package, required, ros_root=env.get(ROS_ROOT))
    if package_dir is None:
        return None
    d = os.path.join(package_dir, subdir)
    if required and os.path.isfile(d):
        raise InvalidROSPkgException(f"Package '{package}' is improperly configured:\n"
                                     f"file {d} is preventing the creation of a directory")
    if required and not os.path.isdir(d):
        try:
            os.makedirs(d)
        except OSError as exc:
            raise InvalidROSPkgException(f"Package '{package}' is improperly configured:\nCannot create a "
                                         f"'{subdir}' directory in {package_dir}.\nPlease check permissions and "
                                         "try again.\n") from exc
    return d


def resource_file(package: str, subdir: str, resource_name: str) -> str:
    """The path of `resource_name` in `package`'s `subdir`; InvalidROSPkgException without the package."""
    d = get_pkg_subdir(package, subdir, False)
    if d is None:
        raise InvalidROSPkgException(package)
    return os.path.join(d, resource_name)


def _executable_filter(test_path: str) -> bool:
    flags = stat.S_IRUSR | stat.S_IXUSR
    return (os.stat(test_path).st_mode & flags) == flags


def _walk(top: str, resource_name: str, filter_fn: Callable[[str], bool] | None) -> list[str]:
    matches = []
    for folder, dirs, files in os.walk(top, followlinks=True):
        if resource_name in files:
            path = os.path.join(folder, resource_name)
            if filter_fn is None or filter_fn(path):
                matches.append(os.path.abspath(path))
        dirs[:] = [d for d in dirs if not d.startswith(".")]
    return matches


def _workspace_dirs(package: str) -> list[str]:
    """The package's libexec (lib/<pkg>) and share folders in the first catkin workspace on
    CMAKE_PREFIX_PATH holding either."""
    for entry in os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep):
        if not entry or not os.path.isfile(os.path.join(entry, ".catkin")):
            continue
        found = [d for d in (os.path.join(entry, "lib", package), os.path.join(entry, "share", package))
                 if os.path.isdir(d)]
        if found:
            return found
    return []


def find_resource(pkg: str, resource_name: str, filter_fn: Callable[[str], bool] | None = None,
                  rospack: rospkg.RosPack | None = None) -> list[str]:
    """Every file named `resource_name` (passing `filter_fn`) in the package's catkin workspace
    folders, then in its source folder; ResourceNotFound without the package."""
    rospack = rospkg.RosPack() if rospack is None else rospack
    package_path = rospack.get_path(pkg)
    matches: list[str] = []
    for top in [*_workspace_dirs(pkg), package_path]:
        matches.extend(m for m in _walk(top, resource_name, filter_fn) if m not in matches)
    return matches


def find_node(pkg: str, node_type: str, rospack: rospkg.RosPack | None = None) -> list[str]:
    """The executables named `node_type` of `pkg`, as roslaunch finds `<node type>`."""
    rospack = rospkg.RosPack() if rospack is None else rospack
    package = Package(pkg, Path(rospack.get_path(pkg)))
    return [str(path) for path in _find_node(package, node_type, os.environ)]


def list_pkgs_by_path(path: str, packages: list[str] | None = None, cache: dict[str, Any] | None = None,
                      env: Mapping[str, str] | None = None) -> list[str]:
    """The rosbuild packages (folders with a manifest.xml) under `path`, appended to `packages`;
    `cache` gets each one's (folder, ROS_ROOT, ROS_PACKAGE_PATH)."""
    packages = [] if packages is None else packages
    env = os.environ if env is None else env
    ros_root, ros_package_path = env[ROS_ROOT], env.get(ROS_PACKAGE_PATH, "")
    for folder, dirs, files in os.walk(os.path.abspath(path), topdown=True):
        if MANIFEST_FILE in files:
            package = os.path.basename(folder)
            if package not in packages:
                packages.append(package)
                if cache is not None:
                    cache[package] = folder, ros_root, ros_package_path
            del dirs[:]
            continue
        if "rospack_nosubdirs" in files:
            del dirs[:]
            continue
        for hidden in (".svn", ".git"):
            if hidden in dirs:
                dirs.remove(hidden)
        for sub in dirs:
            linked = os.path.join(folder, sub)
            if os.path.islink(linked):  # os.walk does not follow links; rosbuild did
                packages.extend(list_pkgs_by_path(linked, cache=cache))
    return packages
