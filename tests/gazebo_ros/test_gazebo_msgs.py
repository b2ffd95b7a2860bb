"""gazebo_msgs as kame ships it: the md5sums ROS's genmsg computes for the same definitions, and
those quoted by public code generated from Noetic's gazebo_msgs."""

from __future__ import annotations

import importlib
import json
import os
import subprocess
from pathlib import Path

import pytest

from tests.support import SYSTEM_PYTHON

SHARE = Path(__file__).resolve().parents[2] / "src" / "kame" / "share"
DEFINITIONS = SHARE / "gazebo_msgs"

# md5sums quoted by code generated from Noetic's gazebo_msgs (rosserial headers, gennodejs, roslisp
# and roseus output, C# and Swift message libraries) and by a gazebo_ros_pkgs issue on a handshake
# that failed over GetModelState.
PUBLISHED = {
    "gazebo_msgs/ModelStates": "48c080191eb15c41858319b4d8a609c2",
    "gazebo_msgs/ModelState": "9330fd35f2fcd82d457e54bd54e10593",
    "gazebo_msgs/ContactsState": "acbcb1601a8e525bf72509f18e6f668d",
    "gazebo_msgs/GetModelState": "4c515e936d3319c9610c559c60bfc3d4",
    "gazebo_msgs/GetWorldProperties": "36bb0f2eccf4d8be971410c22818ba3f",
    "gazebo_msgs/SetLightProperties": "e6f13430c57278bb364aca53a1bf5ebf",
    "gazebo_msgs/SetLightPropertiesRequest": "10d953f2306aec18460eb80dd94fdd47",
    "gazebo_msgs/SetLightPropertiesResponse": "2ec6f3eff0161f4257b808b12bc830c2",
    "gazebo_msgs/GetLightPropertiesResponse": "9a19ddd5aab4c13b7643d1722c709f1f",
    "gazebo_msgs/LinkState": "0818ebbf28ce3a08d48ab1eaa7309ebe",
    "gazebo_msgs/ODEJointProperties": "1b744c32a920af979f53afe2f9c3511f",
    "gazebo_msgs/ODEPhysics": "667d56ddbd547918c32d1934503dc335",
    "gazebo_msgs/PerformanceMetrics": "884f71fd5037b886ec5e126b83c4425a",
    "gazebo_msgs/SpawnModel": "9ed9c82c96abe1a00c3e8cdaeee24413",
    "gazebo_msgs/GetJointProperties": "7b30be900f50aa21efec4a0ec92d91c9",
    "gazebo_msgs/GetPhysicsProperties": "575a5e74786981b7df2e3afc567693a6",
    "gazebo_msgs/ApplyBodyWrench": "585b9f9618aa0581b207e2f2d90866bc",
    "gazebo_msgs/SetModelConfiguration": "10e3139d3b669c40afc057d38956fff7",
}

NOETIC_TYPES = {
    "msg": ["ContactState", "ContactsState", "LinkState", "LinkStates", "ModelState", "ModelStates",
            "ODEJointProperties", "ODEPhysics", "PerformanceMetrics", "SensorPerformanceMetric", "WorldState"],
    "srv": ["ApplyBodyWrench", "ApplyJointEffort", "BodyRequest", "DeleteLight", "DeleteModel", "GetJointProperties",
            "GetLightProperties", "GetLinkProperties", "GetLinkState", "GetModelProperties", "GetModelState",
            "GetPhysicsProperties", "GetWorldProperties", "JointRequest", "SetJointProperties", "SetJointTrajectory",
            "SetLightProperties", "SetLinkProperties", "SetLinkState", "SetModelConfiguration", "SetModelState",
            "SetPhysicsProperties", "SpawnModel"],
}


def kame_md5sums() -> dict[str, str]:
    sums = {}
    for kind, names in NOETIC_TYPES.items():
        module = importlib.import_module(f"gazebo_msgs.{kind}")
        for name in names:
            cls = getattr(module, name)
            sums[cls._type] = cls._md5sum
            if kind == "srv":
                for part in (cls._request_class, cls._response_class):
                    sums[part._type] = part._md5sum
    return sums


def test_every_noetic_definition_is_shipped_and_nothing_else() -> None:
    for kind, names in NOETIC_TYPES.items():
        assert sorted(p.stem for p in (DEFINITIONS / kind).iterdir()) == sorted(names)


def test_md5sums_quoted_from_noetic_gazebo_msgs() -> None:
    sums = kame_md5sums()
    for name, md5 in PUBLISHED.items():
        assert sums[name] == md5, name


@pytest.mark.skipif(not (os.path.exists(SYSTEM_PYTHON) and os.path.isdir("/usr/share/trajectory_msgs/msg")),
                    reason="Debian's genmsg and message definitions are not installed (scripts/install-ros-peers.sh)")
def test_md5sums_equal_debian_genmsg() -> None:
    probe = subprocess.run([SYSTEM_PYTHON, "-c", "import genmsg"], capture_output=True)
    if probe.returncode != 0:
        pytest.skip("Debian's genmsg is not installed")
    result = subprocess.run([SYSTEM_PYTHON, str(Path(__file__).with_name("genmsg_md5.py")), str(SHARE)],
                            capture_output=True, text=True, check=True, timeout=60)
    debian = json.loads(result.stdout)
    assert len(debian) == len(NOETIC_TYPES["msg"]) + 3 * len(NOETIC_TYPES["srv"])
    assert kame_md5sums() == debian
