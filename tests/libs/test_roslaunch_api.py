"""roslaunch's module API: core (Param, Machine, Master, Test), config (ROSLaunchConfig,
load_config_default) and xmlloader (XmlLoader, XmlParseException) on one launch file, the same
answers from kame as from Debian's real roslaunch (tests/libs/launch_driver.py under both)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from . import debian

DRIVER = Path(__file__).with_name("launch_driver.py")
LAUNCH = Path(__file__).with_name("launch_pkg") / "launch" / "demo.launch"


def run(python: str) -> dict[str, Any]:
    env = {**debian.debian_env(), "ROS_MASTER_URI": "http://127.0.0.1:1/", "ROS_PACKAGE_PATH": str(LAUNCH.parents[1])}
    result = subprocess.run([python, str(DRIVER), str(LAUNCH)], capture_output=True, text=True, env=env, timeout=90)
    assert result.returncode == 0, result.stderr
    answer: dict[str, Any] = json.loads(result.stdout.splitlines()[-1])
    return answer


def test_the_launch_file_as_roslaunch_objects() -> None:
    ours = run(sys.executable)
    loaded = ours["loaded"]
    assert loaded["params"] == {"/limits/max": 2.5, "/limits/names": ["a", "b"], "/rate": 7, "/robot_name": "r2",
                                "/sim/background_r": 7}
    assert loaded["nodes"] == [
        ["turtlesim", "turtlesim_node", "sim", "/", "", [["turtle1/cmd_vel", "/cmd"]], True, "screen", False, "here"],
        ["rospy_tutorials", "talker", "talker", "/robot/", "--fast", [], False, None, True, None]]
    assert loaded["tests"] == [["check", 30.0, 2, "check", "rospy_tutorials", "listener"]]
    assert loaded["machines"] == ["", "here"] and loaded["files"] == [str(LAUNCH)]
    assert ours["errors"] == [["XmlParseException", True], ["XmlParseException", True]]
    assert ours["default"]["robot"] == "r9" and ours["default"]["port"] == 11411
    assert ours["default"]["core"][0][:3] == ["rosout", "rosout", "rosout"]
    assert ours["master"] == ["rosmaster", "example.invalid", 1234, True, "a/b"]


@pytest.mark.skipif(not debian.has("roslaunch.config", "roslaunch.xmlloader"),
                    reason="Debian's python3-roslaunch is not installed")
def test_the_same_answers_as_debians_roslaunch() -> None:
    assert run(sys.executable) == run(str(debian.SYSTEM_PYTHON))
