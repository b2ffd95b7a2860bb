"""Debian's ROS 1 tools against kame's stageros and map_server: they read the scan, odometry, tf
and map, call static_map, and drive the robot with their rostopic pub."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.support import SYSTEM_PYTHON, Proc, have_debian_ros, ros_tool
from tests.turtlesim.sim import master, wait_until

pytestmark = pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 is not installed")
OFFICE = str(Path(__file__).resolve().parents[2] / "src" / "kame" / "share" / "turtlebot_gazebo" / "worlds"
             / "office.yaml")


def test_debian_tools_read_and_drive_the_simulation(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        sim.start("stage_ros", "stageros", OFFICE, wait="Simulating [robot_0]")
        sim.start("map_server", "map_server", OFFICE, wait="Read a 320 X 240 map")

        def echo(topic: str) -> dict[str, Any]:
            out = ros_tool("rostopic", "echo", "-n", "1", topic, env=sim.env).stdout
            data = yaml.safe_load(out.split("---")[0])
            assert isinstance(data, dict), out
            return data

        scan = echo("/base_scan")
        assert scan["range_max"] == 10.0 and len(scan["ranges"]) == 640
        assert [t["child_frame_id"] for t in echo("/tf")["transforms"]] == [
            "base_footprint", "base_link", "base_scan"]
        assert echo("/map/info")["width"] == 320
        assert "data:" in ros_tool("rosservice", "call", "/static_map", env=sim.env).stdout
        driver = Proc([SYSTEM_PYTHON, "/usr/bin/rostopic", "pub", "-r", "10", "/cmd_vel", "geometry_msgs/Twist",
                       "{linear: {x: 0.4}}"], sim.env, cwd=sim.home)
        sim.procs.append(driver)

        def x() -> float:
            pose = echo("/base_pose_ground_truth")["pose"]
            return float(pose["pose"]["position"]["x"])

        wait_until(lambda: x() > 0.3, timeout=30, what="Debian's rostopic pub to drive the robot")
