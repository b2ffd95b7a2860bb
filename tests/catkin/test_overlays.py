"""Python-only workspaces chained as catkin chains them, kame's catkin_make beside Debian's.

ws1 is built on nothing; ws2 after `source ws1/devel/setup.bash`, with one more prefix that is
no catkin workspace (a folder with lib/) on CMAKE_PREFIX_PATH. Each implementation builds its
own copy (Debian's with the system's environment: no ROS variables, /usr/bin first); the
lines catkin prints about the prefixes and the environment `source ws2/devel/setup.bash`
gives in a fresh shell must be the same, but for what only kame has (its interpreter's bin/
on PATH, its share folder on ROS_PACKAGE_PATH, roslisp's ROSLISP_PACKAGE_DIRECTORIES, which
Debian does not package). Then, where there is a C++ toolchain, ws3's C++ package is built on
ws2 and finds ws2's Python package and message package with find_package(catkin REQUIRED
COMPONENTS ...), and the message's header, as it finds catkin's. The builds run once for the module."""

from __future__ import annotations

import shutil
import subprocess
import textwrap
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pytest

from kame.catkin.toolchain import Missing, find_toolchain
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


Runner = Callable[[str], subprocess.CompletedProcess[str]]
NODE = """#include <ros/ros.h>
#include <ws2_msgs/Num.h>
int main(int argc, char** argv) {
  ws2_msgs::Num num;
  num.num = 7;
  std::cout << ros::message_traits::datatype(num) << " " << num.num << " "
            << ros::message_traits::md5sum(num) << std::endl;
  return 0;
}
"""


def _message_package(src: Path) -> None:
    """ws2_msgs: a message package with no C++ target (kame's build: no headers in its devel)."""
    folder = src / "ws2_msgs"
    (folder / "msg").mkdir(parents=True)
    (folder / "msg" / "Num.msg").write_text("int64 num\n")
    (folder / "package.xml").write_text(PACKAGE_XML.format(name="ws2_msgs").replace(
        "<exec_depend>rospy</exec_depend>",
        "<build_depend>message_generation</build_depend>\n  <exec_depend>message_runtime</exec_depend>"))
    (folder / "CMakeLists.txt").write_text(
        "cmake_minimum_required(VERSION 3.0.2)\nproject(ws2_msgs)\n"
        "find_package(catkin REQUIRED COMPONENTS message_generation)\n"
        "add_message_files(FILES Num.msg)\ngenerate_messages()\n"
        "catkin_package(CATKIN_DEPENDS message_runtime)\n")


@dataclass
class Chain:
    root: Path
    run: Runner
    ws1: list[str]  # the lines on the prefixes each build printed (root as ROOT)
    ws2: list[str]
    env: dict[str, list[str]]  # the entries below root of each variable ws2's setup.bash gives


def _chain(root: Path, run: Runner) -> Chain:
    """Build ws1, then ws2 on top of it (and of root/other); what they printed and ws2's environment."""
    for ws, python in (("ws1", False), ("ws2", True)):
        _package(root / ws / "src", f"{ws}_pkg", python)
    _message_package(root / "ws2" / "src")
    (root / "other" / "lib").mkdir(parents=True)
    first = run(f"cd {root}/ws1 && catkin_make")
    second = run(f"source {root}/ws1/devel/setup.bash && export CMAKE_PREFIX_PATH=$CMAKE_PREFIX_PATH:{root}/other "
                 f"&& cd {root}/ws2 && catkin_make")
    shown = run(f"source {root}/ws2/devel/setup.bash && " +
                " && ".join(f'echo "{name}=${{{name}:-}}"' for name in COMPARED))
    for done in (first, second, shown):
        assert done.returncode == 0, done.stdout + done.stderr
    env = dict(line.split("=", 1) for line in shown.stdout.splitlines() if "=" in line)
    return Chain(root, run, _prefix_lines(first.stdout, root), _prefix_lines(second.stdout, root),
                 {name: [p.replace(str(root), "ROOT") for p in env[name].split(":") if p.startswith(str(root))]
                  for name in COMPARED})


def _cpp_overlay(chain: Chain) -> tuple[subprocess.CompletedProcess[str], subprocess.CompletedProcess[str]]:
    """ws3: a C++ package needing roscpp and ws2's packages (including a header of ws2_msgs), built after
    sourcing ws2; its build and its run."""
    folder = chain.root / "ws3" / "src" / "ws3_node"
    folder.mkdir(parents=True)
    (folder / "package.xml").write_text(PACKAGE_XML.format(name="ws3_node").replace(
        "<exec_depend>rospy</exec_depend>",
        "<depend>roscpp</depend>\n  <depend>ws2_pkg</depend>\n  <depend>ws2_msgs</depend>"))
    (folder / "CMakeLists.txt").write_text(
        "cmake_minimum_required(VERSION 3.0.2)\nproject(ws3_node)\n"
        "find_package(catkin REQUIRED COMPONENTS roscpp ws2_pkg ws2_msgs)\ncatkin_package()\n"
        "include_directories(${catkin_INCLUDE_DIRS})\nadd_executable(node node.cpp)\n"
        "target_link_libraries(node ${catkin_LIBRARIES})\n")
    (folder / "node.cpp").write_text(NODE)
    built = chain.run(f"source {chain.root}/ws2/devel/setup.bash && cd {chain.root}/ws3 && catkin_make")
    ran = chain.run(f"source {chain.root}/ws3/devel/setup.bash && rosrun ws3_node node")
    return built, ran


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
def kame_cpp(kame: Chain) -> tuple[subprocess.CompletedProcess[str], subprocess.CompletedProcess[str]]:
    if isinstance(find_toolchain(clean_env(kame.root)), Missing):
        pytest.skip("no C++ toolchain (cmake, make, c++, catkin, roscpp): no C++ overlay to build")
    return _cpp_overlay(kame)


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


def test_a_cpp_package_finds_a_python_package_of_the_workspace_it_overlays(
        debian: Chain, kame: Chain,
        kame_cpp: tuple[subprocess.CompletedProcess[str], subprocess.CompletedProcess[str]]) -> None:
    debian_built, debian_ran = _cpp_overlay(debian)
    built, ran = kame_cpp
    for done, chain in ((debian_built, debian), (built, kame)):
        assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
        assert _prefix_lines(done.stdout, chain.root) == [
            "-- Using CMAKE_PREFIX_PATH: ROOT/ws2/devel;ROOT/ws1/devel;ROOT/other",
            "-- This workspace overlays: ROOT/ws2/devel;ROOT/ws1/devel"]
    assert debian_ran.stdout == ran.stdout == "ws2_msgs/Num 7 57d3c40ec3ac3754af76a83e6e73127a\n", ran.stderr
