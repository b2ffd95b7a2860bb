"""roslib.msgs (rosbuild's message specs) over kame's parser: the same specs, parsed types and
checks as Debian's roslib on the same cases (tests/libs/roslib_msgs_driver.py under both)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from . import debian

DRIVER = Path(__file__).with_name("roslib_msgs_driver.py")
DEBIAN_STD_MSGS = Path("/usr/share/std_msgs")
REQUEST = {
    "texts": [["Header header\nint32 x # the x\nfloat64[] values\nPoint p\ngeometry_msgs/Pose[2] poses\n", "pkg"],
              ["int32 A=3\nstring S=hello # not a comment\nbool B=1\nuint8 u\n", ""],
              ["Header stamp\ntime t\n", "pkg"], ["int32 x\nint32 x\n", "pkg"], ["int32\n", "pkg"],
              ["int32 bad-name\n", "pkg"], ["", "pkg"]],
    "types": ["int32", "int32[]", "int32[4]", "std_msgs/String[]", "Header", "String", "int32[x]", "int32[][]",
              "", "a b", "pkg/T[3][2]"],
}


def run(python: str) -> dict[str, Any]:
    env = debian.debian_env()
    if DEBIAN_STD_MSGS.is_dir():  # Debian's roslib finds packages under ROS_ROOT and ROS_PACKAGE_PATH only
        env.update(ROS_ROOT="/usr/share/ros", ROS_PACKAGE_PATH=str(DEBIAN_STD_MSGS))
    result = subprocess.run([python, str(DRIVER)], input=json.dumps(REQUEST), capture_output=True, text=True,
                            timeout=60, env=env)
    assert result.returncode == 0, result.stderr
    answer: dict[str, Any] = json.loads(result.stdout)
    return answer


def test_specs_and_types() -> None:
    ours = run(sys.executable)
    first = ours["loaded"][0]
    assert first[0] == ["Header", "int32", "float64[]", "pkg/Point", "geometry_msgs/Pose[2]"] and first[3] is True
    assert ours["loaded"][1][2] == [["int32", "A", 3, "3"], ["string", "S", "hello # not a comment",
                                                             "hello # not a comment"], ["bool", "B", True, "1"]]
    assert ours["loaded"][3:6] == ["MsgSpecException"] * 3
    assert ours["parsed"][:3] == [["int32", False, None], ["int32", True, None], ["int32", True, 4]]
    assert ours["header"] == ["std_msgs/Header", ["uint32", "time", "string"], ["seq", "stamp", "frame_id"], False]


@pytest.mark.skipif(not (debian.has("roslib.msgs") and DEBIAN_STD_MSGS.is_dir()),
                    reason="Debian's python3-roslib and ros-std-msgs are not installed")
def test_the_same_as_debians_roslib() -> None:
    assert run(sys.executable) == run(str(debian.SYSTEM_PYTHON))
