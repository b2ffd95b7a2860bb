"""roslib.stacks: rosbuild's stacks (folders with a stack.xml) on the package path, over rospkg."""

from __future__ import annotations

import os
import re
from collections.abc import Mapping, Sequence

import rospkg
from roslib import packages as _packages
from roslib import stack_manifest

__all__ = ["ROS_PACKAGE_PATH", "ROS_ROOT", "ROS_STACK", "STACK_FILE", "InvalidROSStackException", "ROSStackException",
           "expand_to_packages", "get_stack_dir", "get_stack_version", "get_stack_version_by_dir", "list_stacks",
           "list_stacks_by_path", "stack_of"]

ROS_ROOT = rospkg.environment.ROS_ROOT
ROS_PACKAGE_PATH = rospkg.environment.ROS_PACKAGE_PATH
STACK_FILE = "stack.xml"
ROS_STACK = "ros"


class ROSStackException(Exception):
    """Base of the stack errors."""


class InvalidROSStackException(ROSStackException):
    """A stack that cannot be found or read."""


def _env(env: Mapping[str, str] | None) -> Mapping[str, str]:
    return os.environ if env is None else env


def _rosstack(env: Mapping[str, str] | None) -> rospkg.RosStack:
    return rospkg.RosStack(rospkg.get_ros_paths(_env(env)))


def stack_of(pkg: str, env: Mapping[str, str] | None = None) -> str | None:
    """The stack `pkg` lies in: the nearest folder above it with a stack.xml."""
    env = _env(env)
    folder = _packages.get_pkg_dir(pkg, ros_root=env.get(ROS_ROOT), ros_package_path=env.get(ROS_PACKAGE_PATH))
    while folder and os.path.dirname(folder) != folder:
        if os.path.exists(os.path.join(folder, STACK_FILE)):
            return os.path.basename(folder)
        folder = os.path.dirname(folder)
    return None


def get_stack_dir(stack: str, env: Mapping[str, str] | None = None) -> str:
    """The folder of `stack`; InvalidROSStackException when there is none."""
    try:
        return _rosstack(env).get_path(stack)
    except rospkg.ResourceNotFound:
        raise InvalidROSStackException(stack) from None


def list_stacks(env: Mapping[str, str] | None = None) -> list[str]:
    return _rosstack(env).list()


def list_stacks_by_path(path: str, stacks: list[str] | None = None, cache: dict[str, str] | None = None) -> list[str]:
    """The stacks under `path` (appended to `stacks`); `cache` gets each one's folder."""
    stacks = [] if stacks is None else stacks
    for folder, dirs, files in os.walk(path, topdown=True):
        if STACK_FILE in files:
            stack = os.path.basename(folder)
            if stack not in stacks:
                stacks.append(stack)
                if cache is not None:
                    cache[stack] = folder
            del dirs[:]
            continue
        if rospkg.MANIFEST_FILE in files or "rospack_nosubdirs" in files:
            del dirs[:]
            continue
        dirs[:] = [d for d in dirs if not d.startswith(".")]
        for sub in dirs:
            linked = os.path.join(folder, sub)
            if os.path.islink(linked):  # os.walk does not follow links; rosbuild did
                stacks.extend(list_stacks_by_path(linked, cache=cache))
    return stacks


def expand_to_packages(names: Sequence[str], env: Mapping[str, str] | None = None) -> tuple[list[str], list[str]]:
    """(the packages `names` name, directly or as stacks; the names that are neither)."""
    ros_paths = rospkg.get_ros_paths(_env(env))
    return rospkg.expand_to_packages(names, rospkg.RosPack(ros_paths), rospkg.RosStack(ros_paths))


def get_stack_version(stack: str, env: Mapping[str, str] | None = None) -> str | None:
    return _rosstack(env).get_stack_version(stack)


def get_stack_version_by_dir(stack_dir: str) -> str | None:
    """The version in the stack's stack.xml, else in its CMakeLists.txt (REP 109)."""
    manifest = os.path.join(stack_dir, STACK_FILE)
    if os.path.isfile(manifest):
        version = stack_manifest.parse_file(manifest).version
        if version:
            return version
    cmake = os.path.join(stack_dir, "CMakeLists.txt")
    if not os.path.isfile(cmake):
        return None
    with open(cmake) as f:
        for line in f.read().split("\n"):
            if line.strip().startswith("rosbuild_make_distribution"):
                parts = re.split(r"[()]", line.strip())
                if len(parts) < 2:
                    raise ROSStackException(f"couldn't find version number in CMakeLists.txt:\n\n{line}")
                return parts[1]
    return None
