"""stageros on a shipped world: cmd_vel moves the robot in odom and ground truth, the scan, tf,
/clock and bumper flow, the command times out; bad input is an error line, never a crash."""

from __future__ import annotations

import math
import struct
import threading
import time
from pathlib import Path

import numpy as np
import pytest
import yaml

from kame.node.node import Node, NodeConfig
from tests.stage.sim import echo
from tests.support import Proc
from tests.turtlesim.sim import BIN, Sim, master, wait_until

WORLDS = Path(__file__).resolve().parents[2] / "src" / "kame" / "share" / "turtlebot_gazebo" / "worlds"
PLAYGROUND = str(WORLDS / "playground.yaml")


def drive(sim: Sim, topic: str, linear: float, angular: float = 0.0) -> Proc:
    proc = Proc([str(BIN / "rostopic"), "pub", "-r", "10", topic, "geometry_msgs/Twist",
                 f"{{linear: {{x: {linear}}}, angular: {{z: {angular}}}}}"], sim.env, cwd=sim.home)
    sim.procs.append(proc)
    return proc


def x_of(sim: Sim, topic: str) -> float:
    return float(echo(sim, topic)["pose"]["pose"]["position"]["x"])


def test_cmd_vel_drives_the_robot_and_every_topic_flows(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        node = sim.start("stage_ros", "stageros", PLAYGROUND, "_initial_pose_x:=3.5", "_initial_pose_y:=-1.0",
                         wait="Simulating [robot_0]")
        scan = echo(sim, "/base_scan")
        assert scan["header"]["frame_id"] == "base_scan" and len(scan["ranges"]) == 640
        ahead = scan["ranges"][320]
        assert ahead == pytest.approx(4.9 - 3.5, abs=0.06)  # the room's east wall, 0.1 m thick at x = 5
        assert x_of(sim, "/base_pose_ground_truth") == pytest.approx(3.5)
        assert echo(sim, "/bumper")["data"] is False
        clock = echo(sim, "/clock")["clock"]
        assert clock["secs"] + clock["nsecs"] > 0
        tf = echo(sim, "/tf")["transforms"]
        assert [(t["header"]["frame_id"], t["child_frame_id"]) for t in tf] == [
            ("odom", "base_footprint"), ("base_footprint", "base_link"), ("base_link", "base_scan")]

        publisher = drive(sim, "/cmd_vel", 0.5)
        wait_until(lambda: echo(sim, "/bumper")["data"] is True, timeout=20, what="the bumper to hit the wall")
        truth = x_of(sim, "/base_pose_ground_truth")
        assert 4.9 - 0.177 - 0.02 < truth < 4.9 - 0.177
        odom = x_of(sim, "/odom")
        assert odom == pytest.approx(truth - 3.5, abs=0.1)  # odometry starts at 0 and drifts a little
        publisher.stop()
        backwards = drive(sim, "/cmd_vel", -0.3, 0.5)
        wait_until(lambda: echo(sim, "/bumper")["data"] is False, timeout=20, what="the bumper to clear")
        backwards.stop()
        wait_until(lambda: echo(sim, "/odom")["twist"]["twist"]["linear"]["x"] == 0.0, timeout=20,
                   what="the command to time out and the robot to stop")
        pose = echo(sim, "/base_pose_ground_truth")["pose"]["pose"]
        assert pose["position"]["y"] != -1.0 and math.isclose(pose["orientation"]["z"] ** 2
                                                              + pose["orientation"]["w"] ** 2, 1.0)
        assert node.popen.poll() is None


@pytest.mark.parametrize("factor", [1.0, 2.0, 0.5])
def test_the_clock_runs_at_the_real_time_factor(tmp_path: Path, factor: float) -> None:
    """/clock against the wall's monotonic clock over 3 s of wall time, read as each message
    arrives; 25% either way, for a loaded 2-core machine (a late step is not made up for)."""
    from rosgraph_msgs.msg import Clock

    ticks: list[tuple[float, float]] = []  # (wall, simulated) seconds
    arrived = threading.Condition()

    def on_clock(frames: list[memoryview], header: dict[str, str]) -> None:
        now = time.monotonic()
        with arrived:
            ticks.extend((now, secs + nsecs * 1e-9) for secs, nsecs in (struct.unpack_from("<II", f) for f in frames))
            arrived.notify_all()

    with master(tmp_path) as sim:
        sim.start("stage_ros", "stageros", "-g", PLAYGROUND, f"_real_time_factor:={factor}",
                  wait="Simulating [robot_0]")
        node = Node(NodeConfig("/clock_watch", sim.uri, "127.0.0.1", "127.0.0.1"))
        try:
            node.subscribe("/clock", "rosgraph_msgs/Clock", Clock._md5sum, Clock._full_text, on_clock)
            with arrived:
                spanned = arrived.wait_for(lambda: bool(ticks) and ticks[-1][0] - ticks[0][0] >= 3.0, timeout=60)
                assert spanned, f"/clock for 3 s of wall time: {len(ticks)} messages"
                (wall0, sim0), (wall1, sim1) = ticks[0], ticks[-1]
        finally:
            node.shutdown("test over")
    assert (sim1 - sim0) / (wall1 - wall0) == pytest.approx(factor, rel=0.25)


def test_nan_commands_are_refused_and_the_robot_goes_on(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        node = sim.start("stage_ros", "stageros", PLAYGROUND, wait="Simulating [robot_0]")
        sim.run("rostopic", "pub", "-1", "/cmd_vel", "geometry_msgs/Twist", "{linear: {x: .nan}}")
        wait_until(lambda: any("Ignoring a cmd_vel for [robot_0]: refusing a velocity that is not finite" in line
                               for line in node.err), what="the warning")
        assert x_of(sim, "/base_pose_ground_truth") == 0.0
        drive(sim, "/cmd_vel", 0.3)
        wait_until(lambda: x_of(sim, "/base_pose_ground_truth") > 0.2, timeout=20, what="the robot to move")


def test_a_box_placed_while_running_is_seen_and_one_on_the_robot_is_refused(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        node = sim.start("stage_ros", "stageros", PLAYGROUND, "_initial_pose_x:=3.5", "_initial_pose_y:=-1.0",
                         wait="Simulating [robot_0]")
        assert echo(sim, "/base_scan")["ranges"][320] == pytest.approx(1.4, abs=0.06)
        placed = yaml.safe_load(sim.run("rosservice", "call", "/stageros/add_box",
                                        "{x: 4.1, y: -1.0, width: 0.2, depth: 0.6}").stdout)
        assert placed == {"success": True, "message": ""}
        node.wait_line("Placed a box of 0.2 x 0.6 m at (4.1, -1)")
        wait_until(lambda: echo(sim, "/base_scan")["ranges"][320] == pytest.approx(0.5, abs=0.06), timeout=20,
                   what="the laser to stop at the box's face")
        refused = yaml.safe_load(sim.run("rosservice", "call", "/stageros/add_box",
                                         "{x: 3.5, y: -1.0, width: 0.5, depth: 0.5}").stdout)
        assert refused["success"] is False and "would cover robot [robot_0]" in refused["message"]
        drive(sim, "/cmd_vel", 0.4)
        wait_until(lambda: echo(sim, "/bumper")["data"] is True, timeout=20, what="the box to stop the robot")
        assert x_of(sim, "/base_pose_ground_truth") < 4.0 - 0.177 + 0.01


def test_reset_positions_puts_the_robot_back_at_its_start_pose(tmp_path: Path) -> None:
    """stageros's reset_positions service (std_srvs/Empty, in its namespace): ground truth at the
    initial pose, odometry at its origin again."""
    with master(tmp_path) as sim:
        node = sim.start("stage_ros", "stageros", PLAYGROUND, "_initial_pose_x:=3.5", "_initial_pose_y:=-1.0",
                         "_initial_pose_a:=0.3", wait="Simulating [robot_0]")
        backwards = drive(sim, "/cmd_vel", -0.4, 0.3)
        wait_until(lambda: x_of(sim, "/base_pose_ground_truth") < 3.0, timeout=20, what="the robot to back away")
        backwards.stop()
        wait_until(lambda: echo(sim, "/odom")["twist"]["twist"]["linear"]["x"] == 0.0, timeout=20,
                   what="the command to time out and the robot to stop")
        assert x_of(sim, "/odom") < -0.4
        sim.run("rosservice", "call", "/reset_positions")
        node.wait_line("Resetting stage!")
        pose = echo(sim, "/base_pose_ground_truth")["pose"]["pose"]
        assert (pose["position"]["x"], pose["position"]["y"]) == (3.5, -1.0)
        assert 2 * math.atan2(pose["orientation"]["z"], pose["orientation"]["w"]) == pytest.approx(0.3)
        odom = echo(sim, "/odom")["pose"]["pose"]
        assert (odom["position"]["x"], odom["position"]["y"], odom["orientation"]["z"]) == (0.0, 0.0, 0.0)
        tf = echo(sim, "/tf")["transforms"][0]["transform"]["translation"]
        assert (tf["x"], tf["y"]) == (0.0, 0.0)


def test_several_robots_have_namespaces(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        sim.run("rosparam", "set", "/stageros/robots", "[{name: r1, x: 0, y: 0}, {name: r2, x: 0, y: 1.5, a: 1.57}]")
        sim.start("stage_ros", "stageros", PLAYGROUND, wait="Simulating [r1], [r2]")
        drive(sim, "/r2/cmd_vel", 0.4)
        wait_until(lambda: echo(sim, "/r2/base_pose_ground_truth")["pose"]["pose"]["position"]["y"] > 1.7,
                   timeout=20, what="r2 to move")
        assert x_of(sim, "/r1/base_pose_ground_truth") == 0.0
        assert echo(sim, "/r2/base_scan")["header"]["frame_id"] == "r2/base_scan"


@pytest.mark.parametrize(("args", "error"), [
    ((PLAYGROUND, "_initial_pose_x:=4.95"), "cannot place [robot_0] at (4.950, 0.000): inside a wall"),
    (("nowhere.yaml",), "Map_server could not open nowhere.yaml."),
    ((PLAYGROUND, "_laser_range_max:=-1"), "the laser's range must satisfy"),
    ((PLAYGROUND, "_robots:=[{name: 'not a name'}]"), "'not a name' is not a legal ROS name"),
])
def test_bad_starts_say_why(tmp_path: Path, args: tuple[str, ...], error: str) -> None:
    with master(tmp_path) as sim:
        result = sim.run("rosrun", "stage_ros", "stageros", *args, check=False)
        assert result.returncode == 1 and error in result.stderr and "Traceback" not in result.stderr, result.stderr


def test_a_stage_world_file(tmp_path: Path) -> None:
    from PIL import Image

    from tests.stage.test_worldfile import MAZE_WORLD, TURTLEBOT_INC

    (tmp_path / "turtlebot.inc").write_text(TURTLEBOT_INC)
    (tmp_path / "maze.world").write_text(MAZE_WORLD)
    Image.fromarray(np.full((20, 40), 255, dtype=np.uint8), "L").save(tmp_path / "maze.png")
    (tmp_path / "gazebo.world").write_text('<?xml version="1.0"?>\n<sdf version="1.4"></sdf>\n')
    with master(tmp_path / "home") as sim:
        sim.start("stage_ros", "stageros", str(tmp_path / "maze.world"), wait="Simulating [robot_0], [robot_1]")
        pose = echo(sim, "/robot_1/base_pose_ground_truth")["pose"]["pose"]
        assert (pose["position"]["x"], pose["position"]["y"]) == (0.5, 1.5)
        assert pose["orientation"]["z"] == pytest.approx(-math.sin(math.pi / 4))
        scan = echo(sim, "/robot_0/base_scan")  # facing +y from (1, 0.5): the boundary at y = 1.95
        assert scan["ranges"][320] == pytest.approx(1.95 - 0.5, abs=0.01)
        result = sim.run("rosrun", "stage_ros", "stageros", str(tmp_path / "gazebo.world"), check=False)
        assert result.returncode == 1 and "is a Gazebo (SDF) world" in result.stderr
