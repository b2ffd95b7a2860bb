"""rospack end to end: the installed console script on a temporary workspace, as a user types it.

The first part pins kame's output; the second runs Debian's real rospack (C++, rospack-tools)
on the same workspace and compares, where both see the same packages (the workspace's own,
and std_msgs whose dependency chain kame models on Noetic's).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

BIN = Path(sys.executable).parent
KAME_SHARE = Path(__file__).resolve().parents[2] / "src" / "kame" / "share"
REAL_ROSPACK = "/usr/bin/rospack"

Result = subprocess.CompletedProcess[str]


def write_package(root: Path, name: str, body: str, fmt: str = "2", folder: str | None = None) -> Path:
    path = root / (folder or name)
    path.mkdir(parents=True, exist_ok=True)
    (path / "package.xml").write_text(
        f'<?xml version="1.0"?>\n<package format="{fmt}">\n  <name>{name}</name>\n  <version>1.2.3</version>\n'
        f'  <description>{name}</description>\n  <maintainer email="a@b.c">me</maintainer>\n'
        f"  <license>BSD</license>\n{body}</package>\n")
    return path


@pytest.fixture(scope="module")
def workspace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    src = tmp_path_factory.mktemp("ws") / "src"
    write_package(src, "alpha", """  <buildtool_depend>catkin</buildtool_depend>
  <build_depend>message_generation</build_depend>
  <depend>beta</depend>
  <exec_depend>gamma</exec_depend>
  <exec_depend>libboost-dev</exec_depend>
  <test_depend>delta</test_depend>
  <build_export_depend>epsilon</build_export_depend>
""")
    write_package(src, "beta", "  <exec_depend>gamma</exec_depend>\n  <depend>std_msgs</depend>\n")
    write_package(src, "gamma", "  <run_depend>delta</run_depend>\n  <build_depend>epsilon</build_depend>\n", fmt="1")
    write_package(src, "delta", '  <exec_depend condition="$ROS_VERSION == 2">epsilon</exec_depend>\n'
                                '  <exec_depend condition="$ROS_VERSION == 1">zeta</exec_depend>\n', fmt="3")
    write_package(src, "epsilon", "")
    write_package(src, "zeta", "")
    write_package(src / "nested", "inner", "  <exec_depend>epsilon</exec_depend>\n")
    (src / "empty" / "deeper").mkdir(parents=True)
    write_package(src / "ignored", "hidden_pkg", "")
    (src / "ignored" / "CATKIN_IGNORE").touch()
    # a hand-written manifest without license or maintainer: catkin_pkg refuses it, rospack reads it
    (src / "sloppy").mkdir()
    (src / "sloppy" / "package.xml").write_text(
        '<package format="2"><name>sloppy</name><exec_depend>zeta</exec_depend></package>')
    write_package(src, "beginner_tutorials", "".join(
        f"  <{tag}>{dep}</{tag}>\n" for tag in ("build_depend", "build_export_depend", "exec_depend")
        for dep in ("roscpp", "rospy", "std_msgs")))
    return src


def env_for(path: Path | str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
    env["ROS_PACKAGE_PATH"] = str(path)
    return env


def kame(ws: Path, *args: str, cwd: Path | None = None) -> Result:
    return subprocess.run([str(BIN / "rospack"), *args], env=env_for(ws), capture_output=True, text=True,
                          cwd=cwd, timeout=30)


def lines(text: str) -> list[str]:
    return text.splitlines()


def test_find_and_list(workspace: Path) -> None:
    assert kame(workspace, "find", "alpha").stdout == f"{workspace / 'alpha'}\n"
    assert kame(workspace, "find", "inner").stdout == f"{workspace / 'nested' / 'inner'}\n"
    assert kame(workspace, "find", "turtlesim").stdout == f"{KAME_SHARE / 'turtlesim'}\n"
    listed = lines(kame(workspace, "list").stdout)
    assert listed == sorted(listed)
    assert f"alpha {workspace / 'alpha'}" in listed
    assert f"rospy_tutorials {KAME_SHARE / 'rospy_tutorials'}" in listed
    names = lines(kame(workspace, "list-names").stdout)
    assert names == [line.split()[0] for line in listed]
    for shipped in ("std_msgs", "geometry_msgs", "turtlesim", "rospy_tutorials", "actionlib_tutorials", "roscpp",
                    "rospy", "catkin", "message_generation", "message_runtime", "genmsg", "genpy"):
        assert shipped in names
    assert "hidden_pkg" not in names


def test_errors(workspace: Path) -> None:
    found = kame(workspace, "find", "nope")
    assert (found.returncode, found.stdout, found.stderr) == (1, "", "[rospack] Error: package 'nope' not found\n")
    for command in ("depends", "depends1", "depends-on", "depends-on1"):
        result = kame(workspace, command, "nope")
        assert (result.returncode, result.stderr) == (1, "[rospack] Error: no such package nope\n")
    quiet = kame(workspace, "-q", "find", "nope")
    assert (quiet.returncode, quiet.stderr) == (1, "")
    assert kame(workspace, "bogus").stderr == "[rospack] Error: command bogus not implemented\n"
    none = kame(workspace)
    assert (none.returncode, none.stderr) == (0, "[rospack] Error: no command given.  Try 'rospack help'\n")
    extra = kame(workspace, "find", "a", "b")
    assert extra.returncode == 1 and "too many positional options" in extra.stderr
    assert kame(workspace, "list-names", "x").stderr == "[rospack] Error: invalid option(s) given\n"
    no_pkg = kame(workspace, "depends1", cwd=workspace)
    assert (no_pkg.returncode, no_pkg.stderr) == (1, "[rospack] Error: no package given\n")


def test_dependencies(workspace: Path) -> None:
    # exec_depend before depend; build/test/export-only and unknown names left out; conditions not evaluated
    assert lines(kame(workspace, "depends1", "alpha").stdout) == ["gamma", "beta"]
    assert lines(kame(workspace, "depends1", "delta").stdout) == ["epsilon", "zeta"]
    assert lines(kame(workspace, "depends1", "sloppy").stdout) == ["zeta"]
    assert lines(kame(workspace, "deps", "alpha").stdout) == [
        "epsilon", "zeta", "delta", "gamma", "cpp_common", "rostime", "roscpp_traits", "roscpp_serialization",
        "catkin", "genmsg", "genpy", "message_runtime", "std_msgs", "beta"]
    assert lines(kame(workspace, "depends-indent", "gamma").stdout) == ["delta", "  epsilon", "  zeta"]
    assert lines(kame(workspace, "depends-on", "delta").stdout) == ["alpha", "beta", "gamma"]
    assert lines(kame(workspace, "depends-on1", "epsilon").stdout) == ["delta", "inner"]
    manifests = kame(workspace, "depends-manifests", "gamma").stdout
    assert manifests == " ".join(str(workspace / p / "package.xml") for p in ("epsilon", "zeta", "delta")) + "\n"
    # the current folder is the default package, by its folder name
    assert lines(kame(workspace, "depends1", cwd=workspace / "gamma").stdout) == ["delta"]


def test_beginner_tutorials_as_on_noetic(workspace: Path) -> None:
    assert lines(kame(workspace, "depends1", "beginner_tutorials").stdout) == ["roscpp", "rospy", "std_msgs"]
    assert lines(kame(workspace, "depends1", "rospy").stdout) == [
        "genpy", "roscpp", "rosgraph", "rosgraph_msgs", "roslib", "std_msgs"]
    assert lines(kame(workspace, "depends", "beginner_tutorials").stdout) == [
        "cpp_common", "rostime", "roscpp_traits", "roscpp_serialization", "catkin", "genmsg", "genpy",
        "message_runtime", "gencpp", "geneus", "gennodejs", "genlisp", "message_generation", "rosbuild",
        "rosconsole", "std_msgs", "rosgraph_msgs", "xmlrpcpp", "roscpp", "rosgraph", "ros_environment", "rospack",
        "roslib", "rospy"]


def test_cycle_and_broken_manifest(tmp_path: Path) -> None:
    write_package(tmp_path, "p", "  <exec_depend>q</exec_depend>\n")
    write_package(tmp_path, "q", "  <exec_depend>r</exec_depend>\n")
    write_package(tmp_path, "r", "  <exec_depend>q</exec_depend>\n")
    result = kame(tmp_path, "depends", "p")
    assert (result.returncode, result.stdout) == (1, "")
    assert result.stderr == "[rospack] Error: maximum dependency depth exceeded (likely circular dependency: q, r)\n"
    assert lines(kame(tmp_path, "depends1", "p").stdout) == ["q"]
    (tmp_path / "bad").mkdir()
    (tmp_path / "bad" / "package.xml").write_text("<package><name>bad</name>")
    bad = kame(tmp_path, "depends1", "bad")
    assert (bad.returncode, bad.stderr) == (
        1, f"[rospack] Error: error parsing manifest of package bad at {tmp_path / 'bad' / 'package.xml'}\n")
    assert kame(tmp_path, "find", "bad").stdout == f"{tmp_path / 'bad'}\n"


def test_list_duplicates(tmp_path: Path) -> None:
    one = write_package(tmp_path / "one", "twin", "")
    two = write_package(tmp_path / "two", "twin", "")
    result = subprocess.run([str(BIN / "rospack"), "list-duplicates"], capture_output=True, text=True,
                            env=env_for(f"{tmp_path / 'one'}:{tmp_path / 'two'}"))
    assert result.stdout == f"twin\n- {one}\n- {two}\n"
    found = subprocess.run([str(BIN / "rospack"), "find", "twin"], capture_output=True, text=True,
                           env=env_for(f"{tmp_path / 'two'}:{tmp_path / 'one'}"))
    assert found.stdout == f"{two}\n"


def test_profile(workspace: Path) -> None:
    out = lines(kame(workspace, "profile").stdout)
    assert out[0].startswith("Full tree crawl took ") and out[0].endswith(" seconds.")
    assert out[1:6] == [
        "Directories marked with (*) contain no manifest.  You may",
        "want to delete these directories.",
        "To get just of list of directories without manifests,",
        "re-run the profile with --zombie-only",
        "-------------------------------------------------------------",
    ]
    entries = {line[11:]: line[9] for line in out[6:]}
    assert entries[str(workspace)] == " "
    assert entries[str(workspace / "nested")] == " "
    assert entries[str(workspace / "empty")] == "*"
    assert len(out) - 6 <= 20
    assert len(lines(kame(workspace, "profile", "--length=2").stdout)) == 8
    zombies = lines(kame(workspace, "profile", "--zombie-only").stdout)
    assert str(workspace / "empty") in zombies and str(workspace / "empty" / "deeper") in zombies
    assert str(workspace / "nested") not in zombies


def test_help() -> None:
    usage = subprocess.run([str(BIN / "rospack"), "help"], capture_output=True, text=True).stdout
    assert usage.startswith("USAGE: rospack <command> [options] [package]\n  Allowed commands:\n")
    assert subprocess.run([str(BIN / "rospack"), "help", "depends1"], capture_output=True, text=True).stdout == (
        "Usage: rospack depends1[package]\n\n"
        "Print newline-separated, ordered list of immediate dependencies of the package.\n")


# ---- side by side with Debian's rospack ------------------------------------------------------

needs_real = pytest.mark.skipif(not os.path.exists(REAL_ROSPACK) or not shutil.which("rospack", path="/usr/bin"),
                                reason="Debian's rospack is not installed")


def real(ws: Path, *args: str, cwd: Path | None = None) -> Result:
    return subprocess.run([REAL_ROSPACK, *args], env=env_for(ws), capture_output=True, text=True, cwd=cwd,
                          timeout=30)


def _stderr(text: str) -> str:
    # Debian-only noise about rosdep (its cache, or python3-rosdep2 absent), not to be copied
    noise = ("rosdep cache", "could not find python module 'rosdep2.rospack'")
    return "".join(line for line in text.splitlines(True) if not any(n in line for n in noise))


SAME_AS_REAL = [
    ("find", "alpha"), ("find", "inner"), ("find", "nope"), ("-q", "find", "nope"),
    ("depends1", "alpha"), ("depends1", "gamma"), ("depends1", "delta"), ("depends1", "sloppy"),
    ("depends", "alpha"), ("deps", "beta"), ("depends-indent", "alpha"), ("depends-manifests", "gamma"),
    ("depends1", "beginner_tutorials"), ("depends", "nope"), ("depends-on1", "nope"),
    ("help", "find"), ("help", "depends-on"), ("help", "profile"), ("help",), (), ("bogus",),
    ("list-names", "x"),
]


@needs_real
def test_same_as_real_rospack(workspace: Path) -> None:
    def both(args: tuple[str, ...]) -> tuple[tuple[str, ...], Result, Result]:
        return args, kame(workspace, *args), real(workspace, *args)

    with ThreadPoolExecutor(8) as pool:
        runs = list(pool.map(both, SAME_AS_REAL))
    for args, ours, theirs in runs:
        assert (ours.returncode, ours.stdout, _stderr(ours.stderr)) == (
            theirs.returncode, theirs.stdout, _stderr(theirs.stderr)), args


@needs_real
def test_reverse_dependencies_and_lists_as_real_rospack(workspace: Path) -> None:
    # the real one lists reverse dependencies in hash-table order; kame sorts them
    for args in (("depends-on", "delta"), ("depends-on1", "epsilon"), ("depends-on1", "zeta")):
        assert sorted(lines(kame(workspace, *args).stdout)) == sorted(lines(real(workspace, *args).stdout))
    ours = [line for line in lines(kame(workspace, "list").stdout) if str(workspace) in line]
    theirs = [line for line in lines(real(workspace, "list").stdout) if str(workspace) in line]
    assert ours == theirs
    assert lines(kame(workspace, "depends1", cwd=workspace / "gamma").stdout) == lines(
        real(workspace, "depends1", cwd=workspace / "gamma").stdout)
