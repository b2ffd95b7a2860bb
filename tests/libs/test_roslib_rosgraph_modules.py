"""roslib's gentools, srvs, msgs and message helpers, and rosgraph's masterapi, xmlrpc and
roslogging, as ROS 1's: each driver runs under kame's interpreter and Debian's /usr/bin/python3
(its real roslib and rosgraph), on the same inputs and Debian's .msg files."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from . import debian

HERE = Path(__file__).parent
SHARE = Path("/usr/share")
DEBIAN_PACKAGES = [SHARE / "std_msgs", SHARE / "geometry_msgs", SHARE / "std_srvs"]
needs_debian_messages = pytest.mark.skipif(not all((p / "package.xml").exists() for p in DEBIAN_PACKAGES),
                                           reason="Debian's ros-std-msgs, geometry-msgs and std-srvs are not installed")


def run(python: str | Path, driver: str, env: dict[str, str] | None = None) -> Any:
    full_env = {**debian.debian_env(), "ROS_ROOT": "/usr/share/ros",
                "ROS_PACKAGE_PATH": ":".join(str(p) for p in DEBIAN_PACKAGES), **(env or {})}
    done = subprocess.run([str(python), str(HERE / driver)], capture_output=True, text=True, env=full_env, timeout=120)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


@pytest.fixture(scope="module")
def roslib_kame() -> Any:
    return run(sys.executable, "roslib_modules_driver.py")


@pytest.fixture(scope="module")
def roslib_ros() -> Any:
    if not debian.has("roslib.gentools"):
        pytest.skip("Debian's python3-roslib is not installed")
    return run(debian.SYSTEM_PYTHON, "roslib_modules_driver.py")


@needs_debian_messages
def test_roslib_gentools(roslib_kame: Any, roslib_ros: Any) -> None:
    pose = roslib_kame["gentools"]["geometry_msgs/msg/PoseStamped.msg"]
    assert pose["md5"] == "d3812c3cbc69362b77dc0b19b345f8f5" and pose["uniquedeps"][0] == "std_msgs/Header"
    assert roslib_kame["gentools"]["std_srvs/srv/SetBool.srv"]["md5"] == "09fb03525b03e7ea1fd3992bafd87e16"
    assert roslib_kame["gentools"] == roslib_ros["gentools"]


@needs_debian_messages
def test_roslib_srvs(roslib_kame: Any, roslib_ros: Any) -> None:
    assert roslib_kame["srvs"]["list"] == ["Empty", "SetBool", "Trigger"]
    assert roslib_kame["srvs"] == roslib_ros["srvs"]


@needs_debian_messages
def test_roslib_msgs_helpers(roslib_kame: Any, roslib_ros: Any) -> None:
    assert roslib_kame["msgs"]["parsed"][0] == ["raised", "MsgSpecException", "Invalid array dimension: []"]
    assert roslib_kame["msgs"]["verbose"] == [False, False, True, True]
    assert roslib_kame["msgs"] == roslib_ros["msgs"]


@needs_debian_messages
def test_roslib_message_classes(roslib_kame: Any, roslib_ros: Any) -> None:
    assert roslib_kame["message"]["messages"][0] == [
        "raised", "ValueError", "message type is missing package name: String"]
    assert roslib_kame["message"] == roslib_ros["message"]
