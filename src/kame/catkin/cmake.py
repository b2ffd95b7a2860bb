"""The real CMake and make over a workspace's C/C++ packages, as catkin_make runs them.

Rules:
- catkin_make's commands: `cmake SRC -DCATKIN_DEVEL_PREFIX=.. -DCMAKE_INSTALL_PREFIX=.. -G "Unix Makefiles"`
  in the build space (src/CMakeLists.txt being catkin's toplevel.cmake), then `make -jN -lN`;
  each announced by catkin's banner, their output passed through as it comes.
- CMake is given the packages it builds as CATKIN_WHITELIST_PACKAGES (the Python-only ones are
  kame's), the interpreter of the system's catkin as PYTHON_EXECUTABLE, and each package of
  kame's prefix of message headers (kame/catkin/cpp_messages.py) as its <package>_DIR cache
  variable, which find_package takes before any prefix (so kame's headers win over the config
  a Python-only underlay has), CMAKE_PREFIX_PATH staying the user's (as catkin's "Using
  CMAKE_PREFIX_PATH" prints it and its setup files record it).
- genmsg is told ROS_LANG_DISABLE=genpy: Python programs import a package's messages through
  kame's import hook (from its .msg files, as for the Python-only packages), not genpy's modules.
- CMake runs without kame's ROS_DISTRO: the system's catkin environment hooks set their own
  (Debian's 1.ros_distro.sh prints a warning that breaks catkin's generate_cached_setup.py
  when another is set).
- cmake runs again only when catkin_make would (inputs_changed, --force-cmake); else
  `make cmake_check_build_system`, as catkin_make.
- make's job flags as catkin's: the user's -j/-l, else none when MAKEFLAGS has some, else
  ROS_PARALLEL_JOBS, else -jN -lN with N the number of processors.
"""

from __future__ import annotations

import os
import re
import subprocess
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

from kame.catkin.toolchain import Toolchain

_JOBS = re.compile(r"(?:^|\s)(-?(?:j|l)(?:\s*[0-9]+|\s|$))"
                   r"|(?:^|\s)((?:--)?(?:jobs|load-average)(?:(?:=|\s+)[0-9]+|(?:\s|$)))")
TOPLEVEL_LINK = "CMakeLists.txt"


class CMakeFailed(Exception):
    """A command failed; the message is catkin_make's."""


def make_arguments(given: Sequence[str], env: Mapping[str, str], cpus: int) -> list[str]:
    args = list(given)
    if _JOBS.search(" ".join(args)):
        return args
    if _JOBS.search(env.get("MAKEFLAGS", "")):
        return args
    if "ROS_PARALLEL_JOBS" in env:
        return args + env["ROS_PARALLEL_JOBS"].split()
    return [*args, f"-j{cpus}", f"-l{cpus}"]


def banner(cmd: Sequence[str], cwd: Path, color: bool) -> list[str]:
    """catkin's print_command_banner."""
    if not color:
        return ["####", f'#### Running command: "{" ".join(cmd)}" in "{cwd}"', "####"]
    blue, bold, reset = "\033[34m", "\033[1m", "\033[0m"
    return [f"{blue}####{reset}",
            f'{blue}#### Running command: {bold}"{" ".join(cmd)}"{reset}{blue} in {bold}"{cwd}"{reset}',
            f"{blue}####{reset}"]


def inputs_changed(build: Path, package_paths: Sequence[str], cmake_args: Sequence[str]) -> bool:
    """catkin_make's test for running cmake again: the packages or the cmake arguments changed
    since the last run (build/catkin_make.cache, in catkin's two-line format), or no Makefile."""
    current = f"{os.pathsep.join(sorted(package_paths))}\n{' '.join(cmake_args)}"
    cache = build / "catkin_make.cache"
    try:
        previous = cache.read_text()
    except OSError:
        previous = None
    build.mkdir(parents=True, exist_ok=True)
    cache.write_text(current)
    return previous != current or not (build / "Makefile").is_file()


def link_toplevel(source: Path, toolchain: Toolchain) -> str | None:
    """src/CMakeLists.txt -> catkin's toplevel.cmake, as catkin_init_workspace; the line it prints."""
    link = source / TOPLEVEL_LINK
    if link.exists() or link.is_symlink():
        return None
    link.symlink_to(toolchain.toplevel)
    return f'Creating symlink "{link}" pointing to "{toolchain.toplevel}"'


class CMakeBuild:
    """One configure-and-make of the C/C++ packages of a workspace."""

    def __init__(self, toolchain: Toolchain, source: Path, build: Path, devel: Path, install: Path,
                 env: Mapping[str, str], prefixes: Sequence[Path], say: Callable[[str], None], color: bool,
                 log: Path | None = None, headers: Path | None = None) -> None:
        """`prefixes` go first on CMAKE_PREFIX_PATH; `headers`: kame's prefix of message headers;
        `log`: where the commands' output goes (catkin build's per-package logs); else it is shown."""
        self.toolchain = toolchain
        self.source = source
        self.build = build
        self.devel = devel
        self.install = install
        self.env = dict(env)
        self.env["CMAKE_PREFIX_PATH"] = os.pathsep.join(
            [str(p) for p in prefixes] + [p for p in env.get("CMAKE_PREFIX_PATH", "").split(os.pathsep) if p])
        self.env.pop("ROS_DISTRO", None)  # the system's hooks set theirs (Debian's fails on another's)
        disabled = [g for g in env.get("ROS_LANG_DISABLE", "").split(":") if g]
        self.env["ROS_LANG_DISABLE"] = ":".join([*disabled, *([] if "genpy" in disabled else ["genpy"])])
        self.say = say
        self.color = color
        self.log = log
        self.headers = headers

    def header_arguments(self) -> list[str]:
        """-D<package>_DIR=... for each package of kame's header prefix (an input of inputs_changed:
        CMake's own re-run, from make, would not have them)."""
        if self.headers is None:
            return []
        return [f"-D{config.parent.name}_DIR={config}" for config in sorted(self.headers.glob("share/*/cmake"))]

    def _run(self, cmd: list[str], shown: list[str], cwd: Path, env: dict[str, str]) -> bool:
        if self.log is None:
            for line in banner(shown, cwd, self.color):
                self.say(line)
            return subprocess.run(cmd, cwd=cwd, env=env, check=False).returncode == 0
        self.log.parent.mkdir(parents=True, exist_ok=True)
        with self.log.open("a") as out:
            out.write("\n".join(banner(shown, cwd, False)) + "\n")
            out.flush()
            return subprocess.run(cmd, cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT,
                                  check=False).returncode == 0

    def configure(self, packages: Sequence[str] | None, cmake_args: Sequence[str]) -> None:
        """CMake over the source space (`packages` its whitelist) or, with None, one package's folder."""
        shown = [self.toolchain.cmake, str(self.source), f"-DCATKIN_DEVEL_PREFIX={self.devel}",
                 f"-DCMAKE_INSTALL_PREFIX={self.install}", *cmake_args, "-G", "Unix Makefiles"]
        kame_args = [*([] if packages is None else [f"-DCATKIN_WHITELIST_PACKAGES={';'.join(packages)}"]),
                     f"-DPYTHON_EXECUTABLE={self.toolchain.python}", *self.header_arguments()]
        self.build.mkdir(parents=True, exist_ok=True)
        shown[0] = "cmake"
        if not self._run([self.toolchain.cmake, *shown[1:-2], *kame_args, *shown[-2:]], shown, self.build, self.env):
            raise CMakeFailed('Invoking "cmake" failed')

    def check(self) -> None:
        """`make cmake_check_build_system`: catkin_make's step instead of cmake when nothing changed
        (CMake itself reconfigures if a CMakeLists.txt or package.xml did)."""
        shown = ["make", "cmake_check_build_system"]
        if not self._run([self.toolchain.make, "cmake_check_build_system"], shown, self.build, self.env):
            raise CMakeFailed('Invoking "make cmake_check_build_system" failed')

    def make(self, make_args: Sequence[str], targets: Sequence[str], folder: Path | None = None) -> None:
        """make in the build space, or in one package's `folder` of it (catkin_make --pkg)."""
        args = make_arguments(make_args, self.env, os.cpu_count() or 1)
        shown = ["make", *args, *targets]
        if not self._run([self.toolchain.make, *args, *targets], shown, folder or self.build, self.env):
            raise CMakeFailed(f'Invoking "{" ".join(shown)}" failed')
