"""kame's setup.bash as a user sources it: the ROS_* variables, PATH, and roscd, rosls, rosed,
roscp, roscat with rosbash's behaviour and messages (driven through bash)."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from kame.shell import SHELL_DIR, setup_file
from tests.shell.shell_env import BIN, SETUP_BASH, bash, clean_env, complete

SHARE = Path(__file__).resolve().parents[2] / "src" / "kame" / "share"


def test_kame_setup_prints_the_setup_files() -> None:
    assert Path(SETUP_BASH) == SHELL_DIR / "setup.bash"
    assert Path(SETUP_BASH).is_file()
    out = subprocess.run([str(BIN / "kame-setup"), "--shell", "zsh"], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == str(setup_file("zsh"))
    out = subprocess.run([str(BIN / "python"), "-m", "kame.shell", "--path"], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == SETUP_BASH


def test_environment(tmp_path: Path) -> None:
    env = clean_env(tmp_path)
    result = bash("printenv | grep ^ROS | sort; echo PATH=$PATH; command -v rostopic", env)
    assert result.returncode == 0, result.stderr
    lines = dict(line.split("=", 1) for line in result.stdout.splitlines() if "=" in line)
    assert lines["ROS_MASTER_URI"] == "http://localhost:11311"
    assert lines["ROS_DISTRO"] == "noetic"
    assert lines["ROS_VERSION"] == "1"
    assert lines["ROS_PYTHON_VERSION"] == "3"
    assert lines["ROS_PACKAGE_PATH"].split(":")[-1] == str(SHARE)
    assert lines["ROS_ROOT"] and lines["ROS_ETC_DIR"]
    assert lines["PATH"].split(":")[0] == str(BIN)
    assert result.stdout.splitlines()[-1] == str(BIN / "rostopic")


def test_keeps_a_set_master_uri_and_package_path(tmp_path: Path) -> None:
    env = clean_env(tmp_path, "http://127.0.0.1:12345/")
    env["ROS_PACKAGE_PATH"] = str(tmp_path)
    result = bash("echo $ROS_MASTER_URI; echo $ROS_PACKAGE_PATH; source " + SETUP_BASH + "; echo $ROS_PACKAGE_PATH",
                  env)
    assert result.stdout.splitlines() == ["http://127.0.0.1:12345/", f"{tmp_path}:{SHARE}", f"{tmp_path}:{SHARE}"]


def test_sh_needs_the_folder_and_then_works(tmp_path: Path) -> None:
    env = clean_env(tmp_path)
    sh = SHELL_DIR / "setup.sh"
    bad = subprocess.run(["sh", "-c", f". {sh}; echo status=$?"], env=env, capture_output=True, text=True)
    assert "_KAME_SETUP_DIR" in bad.stderr
    good = subprocess.run(["sh", "-c", f"_KAME_SETUP_DIR={SHELL_DIR} . {sh} && echo $ROS_DISTRO"], env=env,
                          capture_output=True, text=True)
    assert good.stdout.strip() == "noetic", good.stderr


@pytest.mark.skipif(shutil.which("zsh") is None, reason="zsh not installed")
def test_zsh_sources_and_has_the_functions(tmp_path: Path) -> None:
    env = clean_env(tmp_path)
    result = subprocess.run(["zsh", "-f", "-c", f"source {setup_file('zsh')} && echo $ROS_DISTRO && "
                             "roscd rospy_tutorials && pwd && whence -w rosls roscat roscp rosed"],
                            env=env, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines()[:2] == ["noetic", str(SHARE / "rospy_tutorials")]


def test_roscd(tmp_path: Path) -> None:
    env = clean_env(tmp_path)
    result = bash("roscd rospy_tutorials && pwd; roscd rospy_tutorials/scripts && pwd; "
                  "roscd no_such_pkg; echo status=$?; roscd --help; roscd a b; roscd; echo status=$?", env,
                  cwd=tmp_path)
    assert result.stdout.splitlines() == [
        str(SHARE / "rospy_tutorials"),
        str(SHARE / "rospy_tutorials" / "scripts"),
        "roscd: No such package/stack 'no_such_pkg'",
        "status=1",
        "usage: roscd package", "", "Jump to target package.",
        "usage: roscd package", "", "Jump to target package.",
        "Neither ROS_WORKSPACE is set nor a catkin workspace is listed in CMAKE_PREFIX_PATH.  Please set "
        "ROS_WORKSPACE or source a catkin workspace to use roscd with no arguments.",
        "status=1",
    ]


def test_roscd_without_arguments_and_locations(tmp_path: Path) -> None:
    env = clean_env(tmp_path)
    ws = tmp_path / "ws" / "devel"
    ws.mkdir(parents=True)
    (ws / ".catkin").write_text(str(tmp_path / "ws" / "src"))
    (tmp_path / "elsewhere").mkdir()
    env["ROS_LOCATIONS"] = f"place={tmp_path / 'elsewhere'}"
    # (sourcing a setup file rolls back workspaces listed before, so the workspace comes after)
    result = bash(f"export CMAKE_PREFIX_PATH=/nonexistent:{ws}; roscd && pwd; roscd place && pwd; "
                  "ROS_WORKSPACE=/tmp roscd && pwd", env)
    assert result.stdout.splitlines() == [str(ws), str(tmp_path / "elsewhere"), "/tmp"]


def test_roscd_log_without_a_master(tmp_path: Path) -> None:
    env = clean_env(tmp_path, "http://127.0.0.1:9/")
    (tmp_path / "log").mkdir()
    result = bash("roscd log && pwd", env)
    assert result.stdout.strip() == str(tmp_path / "log")
    assert "No active roscore" in result.stderr


def test_rosls_roscat_roscp_rosed(tmp_path: Path) -> None:
    env = clean_env(tmp_path)
    env["EDITOR"] = "echo editing"
    script = (f"rosls rospy_tutorials; echo --; rosls rospy_tutorials/srv; echo --; "
              f"roscat rospy_tutorials AddTwoInts.srv; roscat rospy_tutorials nothing.txt; echo status=$?; "
              f"roscat no_pkg x; echo status=$?; roscat; echo status=$?; "
              f"roscp rospy_tutorials talker {tmp_path}/copy && head -1 {tmp_path}/copy; "
              f"rosed rospy_tutorials Floats.msg")
    result = bash(script, env)
    assert result.stdout.splitlines() == [
        "msg", "package.xml", "scripts", "srv", "--",
        "AddTwoInts.srv", "BadTwoInts.srv", "--",
        "int64 a", "int64 b", "---", "int64 sum",
        "That file does not exist in that package.", "status=1",
        "Couldn't find package [no_pkg]", "status=1",
        "usage: roscat [package] [file]", "", "Display a file content within a package.", "status=1",
        "#!/usr/bin/env python3",
        f"editing {SHARE / 'rospy_tutorials' / 'msg' / 'Floats.msg'}",
    ]


def test_turtlesim_is_laid_out_as_noetic_installs_it(tmp_path: Path) -> None:
    """share/turtlesim as Noetic's (cmake, images, msg, package.xml, srv: no launch files, no
    action), its programs in lib/turtlesim, found by rosrun's completion."""
    env = clean_env(tmp_path)
    result = bash("rosls turtlesim; echo --; rosls turtlesim/images", env)
    assert result.stdout.splitlines() == [
        "cmake", "images", "msg", "package.xml", "srv", "--",
        *(f"{colour}-turtle.png" for colour in ("blue", "brown", "green", "olive", "orange", "red", "teal", "violet"))]
    assert complete(env, "rosrun", "turtlesim", "") == ["draw_square", "mimic", "turtle_teleop_key", "turtlesim_node"]


def test_rosls_unknown_package_is_ls_of_nothing(tmp_path: Path) -> None:
    result = bash("rosls no_such_pkg; echo status=$?", clean_env(tmp_path))
    assert result.stdout.splitlines()[-1] != "status=0"
    assert "ls: cannot access ''" in result.stderr


def test_rosawesome_defines_rosbashs_aliases(tmp_path: Path) -> None:
    result = bash("rosawesome; alias megamaid suck2blow botherder", clean_env(tmp_path))
    assert result.stdout.splitlines() == [
        "alias megamaid='rosbag record'", "alias suck2blow='rosbag play'", "alias botherder='roscore'"]
