"""The C++ toolchain a workspace's C/C++ packages are built with: the system's, found, never ours.

Rules:
- kame does not compile or reimplement CMake: packages with C/C++ targets are configured by
  the real CMake with the system's catkin (its toplevel.cmake and macros), built by make, and
  link the system's roscpp. This module finds those tools and says what is missing.
- Prefixes searched for catkin and roscpp: CMAKE_PREFIX_PATH's, then /opt/ros/noetic, /usr/local
  and /usr (Debian and Ubuntu install ROS 1's packages in /usr).
- catkin's CMake code runs Python scripts (its own, genmsg's, gencpp's) with the interpreter
  catkin was installed for: the one named on the first line of catkin's own catkin_find.
- What is missing is said as an install line for this platform (apt on Debian and Ubuntu).
"""

from __future__ import annotations

import os
import shutil
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from kame.catkin.workspace import WorkspacePackage, unresolved_components
from kame.msg.catalog import find_packages, package_path_roots

DEFAULT_PREFIXES = ("/opt/ros/noetic", "/usr/local", "/usr")
# what to install for each missing piece, on Debian and Ubuntu
APT_PACKAGES = {
    "cmake": "cmake",
    "make": "make",
    "c++": "g++",
    "catkin": "catkin",
    "roscpp": "libroscpp-dev",
}


@dataclass(frozen=True)
class Toolchain:
    cmake: str
    make: str
    toplevel: Path  # catkin's toplevel.cmake, which src/CMakeLists.txt links to
    python: str  # the interpreter catkin's scripts run with


@dataclass(frozen=True)
class Missing:
    pieces: tuple[str, ...]  # keys of APT_PACKAGES

    def advice(self, os_release: str) -> str:
        """What to install here, as one message."""
        fields = dict(line.partition("=")[::2] for line in os_release.splitlines() if "=" in line)
        family = " ".join(fields.get(k, "").strip('"') for k in ("ID", "ID_LIKE")).split()
        what = ", ".join(self.pieces)
        if {"debian", "ubuntu"} & set(family):
            apt = " ".join(APT_PACKAGES[p] for p in self.pieces)
            return (f"The C++ packages need {what}, which this machine lacks. Install them with:\n"
                    f"  sudo apt-get install {apt}\n"
                    "then run catkin_make again.")
        return (f"The C++ packages need {what}, which this machine lacks. Install ROS 1 Noetic's roscpp "
                "and catkin for this platform (ROS 1's own packages on Ubuntu 20.04, RoboStack's "
                "ros-noetic-roscpp with conda elsewhere), CMake, make and a C++ compiler, put their "
                "prefix on CMAKE_PREFIX_PATH, then run catkin_make again.")


def os_release() -> str:
    """/etc/os-release's text (empty where there is none)."""
    try:
        return Path("/etc/os-release").read_text()
    except OSError:
        return ""


def prefixes(env: Mapping[str, str]) -> list[Path]:
    found = [Path(p) for p in env.get("CMAKE_PREFIX_PATH", "").split(os.pathsep) if p]
    return found + [Path(p) for p in DEFAULT_PREFIXES]


def package_config(name: str, search: list[Path]) -> Path | None:
    """The folder of NAMEConfig.cmake in the first prefix that has one (CMake's config-mode folders)."""
    for prefix in search:
        for folder in (prefix / "share" / name / "cmake", prefix / "lib" / "cmake" / name,
                       *sorted((prefix / "lib").glob(f"*/cmake/{name}"))):
            if (folder / f"{name}Config.cmake").is_file() or (folder / f"{name}-config.cmake").is_file():
                return folder
    return None


def interpreter(script: Path) -> str | None:
    """The interpreter a script's #! line names (`/usr/bin/env python3` resolved on PATH)."""
    try:
        with script.open("rb") as fh:
            first = fh.readline().decode(errors="replace").strip()
    except OSError:
        return None
    if not first.startswith("#!"):
        return None
    words = first[2:].split()
    if words and os.path.basename(words[0]) == "env" and len(words) > 1:
        return shutil.which(words[1])
    return words[0] if words else None


def missing_components(packages: list[WorkspacePackage], search: list[Path]) -> dict[str, list[str]]:
    """Per package, the find_package(catkin COMPONENTS ...) names neither the workspace, kame
    (its packages and ROS_PACKAGE_PATH's) nor the system (a NAMEConfig.cmake in `search`) has."""
    known = find_packages(package_path_roots())
    return unresolved_components(packages, lambda name: name in known or package_config(name, search) is not None)


def find_toolchain(env: Mapping[str, str]) -> Toolchain | Missing:
    path = env.get("PATH", os.defpath)
    cmake = shutil.which("cmake", path=path)
    make = shutil.which("make", path=path)
    compiler = env.get("CXX") or shutil.which("c++", path=path) or shutil.which("g++", path=path)
    search = prefixes(env)
    catkin = package_config("catkin", search)
    missing = [name for name, found in (("cmake", cmake), ("make", make), ("c++", compiler), ("catkin", catkin),
                                        ("roscpp", package_config("roscpp", search)))
               if not found]
    if missing or cmake is None or make is None or catkin is None:
        return Missing(tuple(missing))
    toplevel = catkin / "toplevel.cmake"
    python = interpreter(catkin.parent.parent.parent / "bin" / "catkin_find") or shutil.which("python3", path=path)
    if not toplevel.is_file() or python is None:
        return Missing(("catkin",))
    return Toolchain(cmake, make, toplevel, python)
