"""Python-only workspaces chained as catkin chains them, kame's catkin_make beside Debian's.

ws1 is built on nothing; ws2 after `source ws1/devel/setup.bash`, with one more prefix that is
no catkin workspace (a folder with lib/) on CMAKE_PREFIX_PATH. Each implementation builds its
own copy (Debian's with the system's environment: no ROS variables, /usr/bin first); the
lines catkin prints about the prefixes and the environment `source ws2/devel/setup.bash`
gives in a fresh shell must be the same, but for what only kame has (its interpreter's bin/
on PATH, its share folder on ROS_PACKAGE_PATH, roslisp's ROSLISP_PACKAGE_DIRECTORIES, which
Debian does not package). Both builds run once for the module."""

from __future__ import annotations

import shutil
import subprocess
import textwrap
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pytest

from tests.shell.shell_env import bash, clean_env

DEBIAN_CATKIN_MAKE = Path("/usr/bin/catkin_make")
COMPARED = ("CMAKE_PREFIX_PATH", "LD_LIBRARY_PATH", "PKG_CONFIG_PATH", "PYTHONPATH", "ROS_PACKAGE_PATH", "PATH")
PACKAGE_XML = """<?xml version="1.0"?>
<package format="2">
  <name>{name}</name>
  <version>0.2.0</version>
  <description>{name}</description>
  <maintainer email="kame@example.com">kame</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  <exec_depend>rospy</exec_depend>
</package>
"""
SETUP_PY = """from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(packages=['{name}'], package_dir={{'': 'src'}}))
"""


def _package(src: Path, name: str, python: bool) -> None:
    folder = src / name
    (folder / "scripts").mkdir(parents=True)
    (folder / "package.xml").write_text(PACKAGE_XML.format(name=name))
    (folder / "scripts" / "hello").write_text("#!/usr/bin/env python3\nprint('hello')\n")
    (folder / "scripts" / "hello").chmod(0o755)
    cmake = textwrap.dedent(f"""\
        cmake_minimum_required(VERSION 3.0.2)
        project({name})
        find_package(catkin REQUIRED)
        {"catkin_python_setup()" if python else ""}
        catkin_package()
        catkin_install_python(PROGRAMS scripts/hello DESTINATION ${{CATKIN_PACKAGE_BIN_DESTINATION}})
        """)
    (folder / "CMakeLists.txt").write_text(cmake)
    if python:
        (folder / "setup.py").write_text(SETUP_PY.format(name=name))
        (folder / "src" / name).mkdir(parents=True)
        (folder / "src" / name / "__init__.py").write_text("VALUE = 1\n")


@dataclass
class Chain:
    ws1: list[str]  # the lines on the prefixes each build printed (root as ROOT)
    ws2: list[str]
    env: dict[str, list[str]]  # the entries below root of each variable ws2's setup.bash gives


def _chain(root: Path, run: Callable[[str], subprocess.CompletedProcess[str]]) -> Chain:
    """Build ws1, then ws2 on top of it (and of root/other); what they printed and ws2's environment."""
    for ws, python in (("ws1", False), ("ws2", True)):
        _package(root / ws / "src", f"{ws}_pkg", python)
    (root / "other" / "lib").mkdir(parents=True)
    first = run(f"cd {root}/ws1 && catkin_make")
    second = run(f"source {root}/ws1/devel/setup.bash && export CMAKE_PREFIX_PATH=$CMAKE_PREFIX_PATH:{root}/other "
                 f"&& cd {root}/ws2 && catkin_make")
    shown = run(f"source {root}/ws2/devel/setup.bash && " +
                " && ".join(f'echo "{name}=${{{name}:-}}"' for name in COMPARED))
    for done in (first, second, shown):
        assert done.returncode == 0, done.stdout + done.stderr
    env = dict(line.split("=", 1) for line in shown.stdout.splitlines() if "=" in line)
    return Chain(_prefix_lines(first.stdout, root), _prefix_lines(second.stdout, root),
                 {name: [p.replace(str(root), "ROOT") for p in env[name].split(":") if p.startswith(str(root))]
                  for name in COMPARED})


def _prefix_lines(output: str, root: Path) -> list[str]:
    return [line.replace(str(root), "ROOT") for line in output.splitlines()
            if line.startswith(("-- Using CMAKE_PREFIX_PATH:", "-- This workspace overlays:"))]


@pytest.fixture(scope="module")
def debian(tmp_path_factory: pytest.TempPathFactory) -> Chain:
    if not DEBIAN_CATKIN_MAKE.is_file() or shutil.which("cmake", path="/usr/bin:/bin") is None:
        pytest.skip("Debian's catkin (catkin, cmake) is not installed: nothing to compare with")
    root = tmp_path_factory.mktemp("debian")
    env = {"HOME": str(root), "PATH": "/usr/bin:/bin", "LANG": "C.UTF-8"}

    def run(script: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(["bash", "-c", script], env=env, capture_output=True, text=True, timeout=300)

    return _chain(root, run)


@pytest.fixture(scope="module")
def kame(tmp_path_factory: pytest.TempPathFactory) -> Chain:
    root = tmp_path_factory.mktemp("kame")
    env = clean_env(root)

    def run(script: str) -> subprocess.CompletedProcess[str]:
        return bash(script, env)

    return _chain(root, run)


def test_the_first_workspace_overlays_nothing(debian: Chain, kame: Chain) -> None:
    assert debian.ws1 == ["-- Using CMAKE_PREFIX_PATH: "]
    assert kame.ws1 == debian.ws1


def test_the_second_names_the_first_and_the_other_prefix_as_catkin_does(debian: Chain,
                                                                       kame: Chain) -> None:
    assert debian.ws2 == ["-- Using CMAKE_PREFIX_PATH: ROOT/ws1/devel;ROOT/other",
                             "-- This workspace overlays: ROOT/ws1/devel"]
    assert kame.ws2 == debian.ws2


def test_the_second_workspaces_setup_gives_catkins_environment(debian: Chain,
                                                              kame: Chain) -> None:
    assert debian.env == {
        "CMAKE_PREFIX_PATH": ["ROOT/ws2/devel", "ROOT/ws1/devel", "ROOT/other"],
        "LD_LIBRARY_PATH": ["ROOT/ws2/devel/lib", "ROOT/ws1/devel/lib", "ROOT/other/lib"],
        "PKG_CONFIG_PATH": ["ROOT/ws2/devel/lib/pkgconfig", "ROOT/ws1/devel/lib/pkgconfig"],
        "PYTHONPATH": ["ROOT/ws2/devel/lib/python3/dist-packages"],
        "ROS_PACKAGE_PATH": ["ROOT/ws2/src", "ROOT/ws1/src"],
        "PATH": [],
    }
    assert kame.env == debian.env
