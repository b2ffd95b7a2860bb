"""The navigation demo as the TurtleBot lessons run it, on one simulated office for the module:
stageros (the office world, at twice real time, with its odometry's drift) and turtlebot_gazebo's
amcl_demo.launch (map_server, the TurtleBot's amcl and move_base). rviz's "2D Pose Estimate" and
"2D Nav Goal" tools drive the nodes end to end, and amcl's global localisation, called through
the ROS node, finds the robot on a scripted drive."""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml

from tests.nav.test_amcl import OFFICE_DRIVE
from tests.nav.test_amcl_live import OFFICE, pose_of
from tests.stage.sim import echo
from tests.support import Proc
from tests.turtlesim.sim import BIN, Sim, master, wait_until

ROUTE_DRIVER = str(Path(__file__).with_name("route_driver.py"))
START = (0.0, 0.0, 0.0)  # where the office world puts the TurtleBot


@pytest.fixture(scope="module")
def office(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Sim]:
    with master(tmp_path_factory.mktemp("office")) as sim:
        sim.run("rosparam", "set", "/use_sim_time", "true")
        sim.start("stage_ros", "stageros", "-g", OFFICE, "base_scan:=scan", "_real_time_factor:=2.0",
                  "_extra_cmd_vel_topics:=[cmd_vel_mux/input/navi]", wait="Simulating")
        demo = Proc([str(BIN / "roslaunch"), "turtlebot_gazebo", "amcl_demo.launch", f"map_file:={OFFICE}"],
                    sim.env, cwd=sim.home)
        sim.procs.append(demo)
        echo(sim, "/amcl_pose")  # amcl has the map and its first estimate
        yield sim


def truth(sim: Sim) -> tuple[float, float, float]:
    return pose_of(echo(sim, "/base_pose_ground_truth"))


def off_by(found: tuple[float, float, float], expected: tuple[float, float, float]) -> tuple[float, float]:
    """(metres, degrees) between two poses."""
    turn = math.degrees(abs(math.remainder(found[2] - expected[2], 2 * math.pi)))
    return math.hypot(found[0] - expected[0], found[1] - expected[1]), turn


def wait_for_estimate(sim: Sim, topic: str, expected: Callable[[], tuple[float, float, float]], metres: float,
                      degrees: float, timeout: float) -> None:
    samples: list[tuple[float, float]] = []

    def close_enough() -> bool:
        samples.append(off_by(pose_of(echo(sim, topic)), expected()))
        return samples[-1][0] < metres and samples[-1][1] < degrees  # both bounds in one sample

    try:
        wait_until(close_enough, timeout=timeout, what=f"{topic} within {metres} m and {degrees} degrees")
    except AssertionError as exc:
        raise AssertionError(f"{exc}; the last (m, degrees) off seen: {samples[-5:]}") from None


def spread(cloud: dict[str, Any]) -> float:
    """The particles' standard deviation in x, metres (the office is 16 m wide)."""
    return float(np.std([pose["position"]["x"] for pose in cloud["poses"]]))


def yaml_pose(x: float, y: float, yaw: float) -> str:
    return (f"{{position: {{x: {x}, y: {y}}}, "
            f"orientation: {{z: {math.sin(yaw / 2)}, w: {math.cos(yaw / 2)}}}}}")


def test_global_localization_finds_the_robot_on_a_scripted_drive(office: Sim) -> None:
    """A second amcl beside the demo's (in its own namespace, broadcasting no transform), with
    amcl's defaults but odom_model_type "diff-corrected": the TurtleBot's "diff" reads its odometry
    alphas as standard deviations, too little spread for the belief to keep the corridor's mirror
    image alive until the south room's box tells them apart, and it sometimes settles on the
    mirror (as tests/nav/test_amcl.py found in process; here, with amcl's seeds 1 to 6, "diff"
    ended 6.9 m and 179 degrees off, on the mirror, in 2 runs of 6, and "diff-corrected" found the
    robot in all six, within 0.07 m and 1.3 degrees). The drive is that test's route, 37 s of ROS
    time, from where the world puts the robot: this test comes first in the module."""
    sim = office
    metres, degrees = off_by(truth(sim), START)
    assert metres < 0.05 and degrees < 1.0, "the route starts where the world puts the robot"
    amcl = sim.start("amcl", "amcl", "__ns:=global", "scan:=/scan", "static_map:=/static_map",
                     "_base_frame_id:=base_footprint", "_tf_broadcast:=false",
                     "_odom_model_type:=diff-corrected",
                     wait="Received a 320 X 240 map")
    sim.run("rosservice", "call", "/global/global_localization")
    wait_until(lambda: spread(echo(sim, "/global/particlecloud")) > 3.0, timeout=30,
               what="the particles to spread over the map")
    route = Proc([sys.executable, ROUTE_DRIVER, *(f"{v},{w},{t}" for v, w, t in OFFICE_DRIVE)], sim.env,
                 cwd=sim.home)
    sim.procs.append(route)
    route.wait_line("done", timeout=120)
    # amcl updates every 0.2 m: this one at the pose the robot stopped at
    sim.run("rosservice", "call", "/global/request_nomotion_update")
    wait_for_estimate(sim, "/global/amcl_pose", lambda: truth(sim), 0.2, 10.0, timeout=30)
    amcl.stop()


def test_rviz_pose_estimate_and_nav_goal_drive_amcl_and_move_base(office: Sim) -> None:
    """What rviz's tools publish (frame map; the pose estimate with rviz's covariance: 0.5 m in x
    and y, pi/12 in yaw): a pose estimate far from the robot makes the demo's amcl estimate jump
    there, the one at the robot brings it back, and a nav goal has move_base take the robot there."""
    sim = office
    here = truth(sim)
    wrong = (-4.0 if here[0] > 0 else 4.0, 0.0, math.pi / 2)  # along the corridor, turned to the north rooms
    covariance = [0.0] * 36
    covariance[0] = covariance[7] = 0.25
    covariance[35] = (math.pi / 12) ** 2
    for pose in (wrong, here):
        sim.run("rostopic", "pub", "-1", "/initialpose", "geometry_msgs/PoseWithCovarianceStamped",
                f"{{header: {{stamp: now, frame_id: map}}, "
                f"pose: {{pose: {yaml_pose(*pose)}, covariance: {covariance}}}}}")
        wait_for_estimate(sim, "/amcl_pose", lambda: pose, 0.3, 10.0, timeout=30)  # noqa: B023

    goal = max([(2.0, -3.0, 0.0), (-2.0, 3.0, 0.0)], key=lambda g: math.dist(g[:2], here[:2]))
    result = Proc([str(BIN / "rostopic"), "echo", "-n", "1", "/move_base/result", "__name:=nav_goal_result"],
                  sim.env, cwd=sim.home)
    sim.procs.append(result)
    wait_until(lambda: "nav_goal_result" in sim.run("rostopic", "info", "/move_base/result").stdout, timeout=20,
               what="the result's listener")
    sim.run("rostopic", "pub", "-1", "/move_base_simple/goal", "geometry_msgs/PoseStamped",
            f"{{header: {{stamp: now, frame_id: map}}, pose: {yaml_pose(*goal)}}}")
    result.popen.wait(timeout=180)
    result.stop()
    status = yaml.safe_load("".join(result.out).split("---")[0])["status"]
    assert status["status"] == 3, status  # SUCCEEDED
    assert off_by(truth(sim), goal)[0] < 0.25, (goal, truth(sim))
