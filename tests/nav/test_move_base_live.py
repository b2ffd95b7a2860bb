"""`rosrun move_base move_base` on the TurtleBot in the office (turtlebot_world.launch,
map_server, map = odom): a user's actionlib client's goal across the office, through a door, is
reached within 0.25 m; the costmap is published; a goal inside a wall is aborted (status 4).
(Boxes met on the way: tests/nav/test_navigation_loop.py, on the world model.)"""

from __future__ import annotations

import math
import sys
from pathlib import Path

from tests.nav.test_amcl_live import OFFICE, pose_of
from tests.stage.sim import echo
from tests.support import Proc
from tests.turtlesim.sim import BIN, master

CLIENT = str(Path(__file__).with_name("goal_client.py"))


def test_move_base_reaches_a_goal_and_aborts_an_unreachable_one(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        world = Proc([str(BIN / "roslaunch"), "turtlebot_gazebo", "turtlebot_world.launch", f"world_file:={OFFICE}"],
                     sim.env, cwd=sim.home)
        sim.procs.append(world)
        world.wait_line("Simulating [robot_0]", timeout=30)
        sim.start("map_server", "map_server", OFFICE, wait="Read a")
        sim.start("tf2_ros", "static_transform_publisher", "0", "0", "0", "0", "0", "0", "map", "odom")
        move_base = sim.start("move_base", "move_base", "_global_costmap/robot_radius:=0.18")
        reach = Proc([sys.executable, CLIENT, "2.0", "-3.0"], sim.env, cwd=sim.home)
        sim.procs.append(reach)
        line = reach.wait_line("state", timeout=120)
        assert line.split()[1] == "3", line  # SUCCEEDED
        found = pose_of(echo(sim, "/base_pose_ground_truth"))
        assert math.hypot(found[0] - 2.0, found[1] + 3.0) < 0.25
        costmap = echo(sim, "/move_base/global_costmap/costmap", "--noarr")
        assert costmap["info"]["width"] == 320

        wall = Proc([sys.executable, CLIENT, "0.0", "0.98"], sim.env, cwd=sim.home)
        sim.procs.append(wall)
        line = wall.wait_line("state", timeout=60)
        assert line.split()[1] == "4" and "valid plan" in line, line  # ABORTED
        move_base.stop()
        assert move_base.popen.returncode == 0  # Ctrl-C ends it, no SIGKILL needed


def test_amcl_demo_launch_localises_and_drives(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        world = Proc([str(BIN / "roslaunch"), "turtlebot_gazebo", "turtlebot_world.launch", f"world_file:={OFFICE}"],
                     sim.env, cwd=sim.home)
        sim.procs.append(world)
        world.wait_line("Simulating [robot_0]", timeout=30)
        demo = Proc([str(BIN / "roslaunch"), "turtlebot_gazebo", "amcl_demo.launch", f"map_file:={OFFICE}"],
                    sim.env, cwd=sim.home)
        sim.procs.append(demo)
        echo(sim, "/amcl_pose")  # amcl has the map and a first estimate
        reach = Proc([sys.executable, CLIENT, "-2.0", "-3.0"], sim.env, cwd=sim.home)
        sim.procs.append(reach)
        line = reach.wait_line("state", timeout=120)
        assert line.split()[1] == "3", line
        found = pose_of(echo(sim, "/base_pose_ground_truth"))
        assert math.hypot(found[0] + 2.0, found[1] + 3.0) < 0.25
