"""The issue's 'done when': a course script using rospkg.RosPack().get_path,
message_filters.ApproximateTimeSynchronizer and a dynamic_reconfigure server runs unchanged
(`rosrun course_fusion fusion_node.py`, no build step), and is tuned live by dynparam: kame's,
and Debian's real one when installed."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from ..dynamic_reconfigure.test_server import DEBIAN_DYNPARAM, debian_ros_env
from ..support import Proc, free_port, kame_command, ros_env, running, wait_for_master
from . import debian

WORKSPACE = Path(__file__).with_name("course_ws")
SENSORS = Path(__file__).with_name("filters_node.py")  # /left and /right, the right one 0.5 ahead in x


@pytest.fixture
def course_env(tmp_path: Path) -> Iterator[dict[str, str]]:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    environment = ros_env(tmp_path / "home", uri)
    environment["ROS_PACKAGE_PATH"] = str(WORKSPACE)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), environment)
    try:
        wait_for_master(uri, proc=master)
        yield environment
    finally:
        master.stop()


def dynparam(env: dict[str, str], *args: str, debians: bool) -> None:
    command = ([str(debian.SYSTEM_PYTHON), str(DEBIAN_DYNPARAM)] if debians
               else kame_command("kame.cli.rosrun", "dynamic_reconfigure", "dynparam"))
    result = subprocess.run([*command, *args], env=debian_ros_env(env) if debians else env, capture_output=True,
                            text=True, timeout=60)
    assert result.returncode == 0, result.stdout + result.stderr


@pytest.mark.parametrize("debians", [False, True], ids=["kame_dynparam", "debian_dynparam"])
def test_the_course_script_runs_unchanged_and_is_tuned_live(course_env: dict[str, str], debians: bool) -> None:
    if debians and not (DEBIAN_DYNPARAM.exists() and debian.has("rospy", "dynamic_reconfigure.client")):
        pytest.skip("Debian's python3-dynamic-reconfigure is not installed")
    with running([sys.executable, str(SENSORS), "pub"], course_env), \
            running(kame_command("kame.cli.rosrun", "course_fusion", "fusion_node.py"), course_env) as node:
        node.wait_line("gain 1.0 enabled True")
        node.wait_line("fused 100.5", timeout=30)  # offset 100 from the package's file, gain 1 * 0.5
        dynparam(course_env, "set", "/fusion_node", "gain", "4", debians=debians)
        node.wait_line("gain 4.0 enabled True")
        node.wait_line("fused 102.0", timeout=30)
        dynparam(course_env, "set", "/fusion_node", "{gain: 20.0, enabled: false}", debians=debians)
        node.wait_line("gain 10.0 enabled False")  # clamped to the .cfg's maximum
        assert node.popen.poll() is None
