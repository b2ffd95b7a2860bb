"""Package programs: where `<node pkg="P" type="T">` finds its program, and how any package
program is run (roslaunch here, rosrun in kame.cli.rosrun with its own search rules).

Rules: roslaunch looks as roslib.packages.find_node does: the catkin workspaces' lib/P (first
workspace on CMAKE_PREFIX_PATH holding it, else kame's own lib/P in kame/lib), then the package
folder searched recursively (links followed, hidden folders skipped) for a regular file named T
with an execute bit. Python programs (a python shebang, or .py with none) run with this
interpreter, whatever their shebang says, so they import kame's rospy.
"""

from __future__ import annotations

import os
import stat
import sys
from collections.abc import Mapping
from pathlib import Path

from kame.msg.catalog import Package, find_packages, package_path_roots, shipped_programs

_EXEC_BITS = stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH


def packages(env: Mapping[str, str]) -> dict[str, Package]:
    return find_packages(package_path_roots(env.get("ROS_PACKAGE_PATH", "")))


def ros_paths(env: Mapping[str, str]) -> list[str]:
    """The search path rospkg reports in its not-found errors: ROS_ROOT, then ROS_PACKAGE_PATH."""
    found = [env["ROS_ROOT"]] if env.get("ROS_ROOT") else []
    return found + [p for p in env.get("ROS_PACKAGE_PATH", "").split(os.pathsep) if p]


def _catkin_lib(package: str, env: Mapping[str, str]) -> list[Path]:
    for entry in env.get("CMAKE_PREFIX_PATH", "").split(os.pathsep):
        if entry and (Path(entry) / ".catkin").is_file() and (Path(entry) / "lib" / package).is_dir():
            return [Path(entry) / "lib" / package]
    return []


def _walk(top: Path, name: str) -> list[Path]:
    hits: list[Path] = []
    seen: set[str] = set()
    for folder, dirnames, filenames in os.walk(top, followlinks=True):
        real = os.path.realpath(folder)
        if real in seen:
            dirnames.clear()
            continue
        seen.add(real)
        dirnames[:] = sorted(d for d in dirnames if not d.startswith("."))
        if name in filenames:
            path = Path(folder, name)
            if path.is_file() and is_executable(path):
                hits.append(path)
    return hits


def is_executable(path: Path) -> bool:
    """An execute bit for anyone (rosrun's and roslib's test, not os.access)."""
    try:
        return bool(os.stat(path).st_mode & _EXEC_BITS)
    except OSError:
        return False


def find_node(package: Package, node_type: str, env: Mapping[str, str]) -> list[Path]:
    """The executables named `node_type` of `package`, best first."""
    hits: list[Path] = []
    for top in [*(_catkin_lib(package.name, env) or shipped_programs(package.name)), package.path]:
        for hit in _walk(top, node_type):
            if hit not in hits:
                hits.append(hit)
    return hits


def is_python_program(path: Path) -> bool:
    try:
        with open(path, "rb") as f:
            first = f.readline(256)
    except OSError:
        return False
    if first.startswith(b"#!"):
        words = first[2:].decode("utf-8", "replace").split()
        if words and os.path.basename(words[0]) == "env":
            words = [w for w in words[1:] if not w.startswith("-")]
        return bool(words) and os.path.basename(words[0]).startswith("python")
    return path.suffix == ".py"


def command_for(path: Path) -> list[str]:
    """The argv prefix that runs `path`."""
    return [sys.executable, str(path)] if is_python_program(path) else [str(path)]
