"""A ROS client for the 3-D TurtleBot tests, run as its own process with kame's Python: it prints
one JSON line about what it saw, so the test process never holds a node.

    probe.py sensors                 the camera's, depth camera's and scan's first messages, summarised
    probe.py drive TOPIC X_TARGET    publish 0.25 m/s on TOPIC until /odom passes x = X_TARGET
    probe.py map SECONDS             turn in place at 0.6 rad/s for SECONDS of simulated time, and
                                     the first /map made after them
    probe.py kobuki                  the Kobuki's IMU; its cliff events while lifted 0.3 m and dropped;
                                     its bumper events driving into a box spawned ahead, then deleted;
                                     commands/motor_power off and on, commands/reset_odometry
"""

from __future__ import annotations

import json
import math
import queue
import sys
from typing import Any

import numpy as np

import rospy
from gazebo_msgs.msg import ModelState, ModelStates
from gazebo_msgs.srv import DeleteModel, GetModelState, SetModelState, SpawnModel
from geometry_msgs.msg import Pose, Twist
from kobuki_msgs.msg import BumperEvent, CliffEvent, MotorPower
from nav_msgs.msg import OccupancyGrid, Odometry
from sensor_msgs.msg import CameraInfo, Image, Imu, LaserScan, PointCloud2
from std_msgs.msg import Empty


def sensors() -> dict[str, Any]:
    rgb = rospy.wait_for_message("/camera/rgb/image_raw", Image, timeout=30)
    depth = rospy.wait_for_message("/camera/depth/image_raw", Image, timeout=30)
    info = rospy.wait_for_message("/camera/depth/camera_info", CameraInfo, timeout=30)
    points = rospy.wait_for_message("/camera/depth/points", PointCloud2, timeout=30)
    scan = rospy.wait_for_message("/scan", LaserScan, timeout=30)
    pixels = np.frombuffer(bytes(depth.data), dtype="<f4").reshape(depth.height, depth.width)
    colours = np.frombuffer(bytes(rgb.data), dtype=np.uint8)
    return {
        "rgb": [rgb.width, rgb.height, rgb.encoding, rgb.header.frame_id, int(colours.min()), int(colours.max())],
        "depth": [depth.width, depth.height, depth.encoding, depth.header.frame_id],
        "depth_centre": float(pixels[depth.height // 2, depth.width // 2]),
        "depth_finite": float(np.isfinite(pixels).mean()),
        "K": list(info.K),
        "points": [points.width, points.height, points.point_step, points.header.frame_id],
        "scan": {"frame": scan.header.frame_id, "angle_min": scan.angle_min, "increment": scan.angle_increment,
                 "ranges": [r if math.isfinite(r) else None for r in scan.ranges]},
    }


def drive(topic: str, target: float) -> dict[str, Any]:
    commands = rospy.Publisher(topic, Twist, queue_size=1)
    odometry: list[Any] = []
    rospy.Subscriber("/odom", Odometry, odometry.append, queue_size=1)
    rate = rospy.Rate(10)
    while not odometry or odometry[-1].pose.pose.position.x < target:
        if rospy.get_time() > 120:
            break
        command = Twist()
        command.linear.x = 0.25
        commands.publish(command)
        rate.sleep()
    commands.publish(Twist())
    odom = odometry[-1].pose.pose.position
    states = rospy.wait_for_message("/gazebo/model_states", ModelStates, timeout=30)
    truth = states.pose[states.name.index("mobile_base")].position
    return {"odom": [odom.x, odom.y], "truth": [truth.x, truth.y], "sim_time": rospy.get_time()}


def map_while_turning(seconds: float) -> dict[str, Any]:
    """Turn in place for `seconds`, then on until gmapping publishes a map made after them (it
    updates its map only while the robot moves)."""
    commands = rospy.Publisher("/cmd_vel_mux/input/teleop", Twist, queue_size=1)
    grids: list[Any] = []
    rospy.Subscriber("/map", OccupancyGrid, grids.append, queue_size=1)
    rate = rospy.Rate(10)
    done = rospy.get_time() + seconds
    while not grids or grids[-1].header.stamp.to_sec() < done:
        if rospy.get_time() > done + 60:
            raise SystemExit("no map after the turn")
        command = Twist()
        command.angular.z = 0.6
        commands.publish(command)
        rate.sleep()
    commands.publish(Twist())
    grid = grids[-1]
    return {"resolution": grid.info.resolution, "origin": [grid.info.origin.position.x, grid.info.origin.position.y],
            "width": grid.info.width, "height": grid.info.height, "cells": list(grid.data)}


BOX = """<sdf version="1.6"><model name="bump_box"><static>true</static><link name="link"><collision name="c">
  <geometry><box><size>0.2 0.6 0.3</size></box></geometry></collision></link></model></sdf>"""


def events(topic: str, data_class: Any) -> queue.Queue[Any]:
    arrived: queue.Queue[Any] = queue.Queue()
    rospy.Subscriber(topic, data_class, arrived.put, queue_size=50)
    return arrived


def until(arrived: queue.Queue[Any], wanted: list[tuple[int, int]], what: str) -> list[list[int]]:
    """The (which, state) events (a cliff's with its bottom) that arrive until each of `wanted` has been seen."""
    seen: list[list[int]] = []
    missing = set(wanted)
    while missing:
        try:
            event = arrived.get(timeout=30)
        except queue.Empty:
            raise SystemExit(f"no {what}: saw {seen}") from None
        which = event.sensor if hasattr(event, "sensor") else event.bumper
        seen.append([which, event.state, *([event.bottom] if hasattr(event, "bottom") else [])])
        missing.discard((which, event.state))
    return seen


def kobuki() -> dict[str, Any]:
    imu = rospy.wait_for_message("/mobile_base/sensors/imu_data", Imu, timeout=30)
    cliffs = events("/mobile_base/events/cliff", CliffEvent)
    bumps = events("/mobile_base/events/bumper", BumperEvent)
    rospy.wait_for_service("/gazebo/set_model_state", timeout=30)
    state = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)("mobile_base", "world")
    q = state.pose.orientation
    heading = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
    lifted = ModelState(model_name="mobile_base", pose=state.pose, reference_frame="world")
    lifted.pose.position.z += 0.3
    rospy.ServiceProxy("/gazebo/set_model_state", SetModelState)(lifted)
    cliff_events = until(cliffs, [(s, CliffEvent.CLIFF) for s in range(3)] + [(s, CliffEvent.FLOOR) for s in range(3)],
                         "cliff and floor events from all three sensors")

    landed = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)("mobile_base", "world").pose
    box = Pose()
    box.position.x = landed.position.x + 0.35 * math.cos(heading)
    box.position.y = landed.position.y + 0.35 * math.sin(heading)
    box.position.z = 0.15
    box.orientation = landed.orientation
    rospy.ServiceProxy("/gazebo/spawn_sdf_model", SpawnModel)("bump_box", BOX, "", box, "world")
    commands = rospy.Publisher("/mobile_base/commands/velocity", Twist, queue_size=1)
    forward = Twist()
    forward.linear.x = 0.1
    timer = rospy.Timer(rospy.Duration(0.1), lambda _event: commands.publish(forward))
    pressed = until(bumps, [(BumperEvent.CENTER, BumperEvent.PRESSED)], "the centre bumper pressed")
    timer.shutdown()
    commands.publish(Twist())
    rospy.ServiceProxy("/gazebo/delete_model", DeleteModel)("bump_box")
    released = until(bumps, [(BumperEvent.CENTER, BumperEvent.RELEASED)], "the centre bumper released")
    motors = motor_power_and_odometry_reset()
    return {"motors": motors, "imu": {"frame": imu.header.frame_id, "acceleration_z": imu.linear_acceleration.z,
                    "heading": math.atan2(2 * (imu.orientation.w * imu.orientation.z),
                                          1 - 2 * imu.orientation.z ** 2), "truth_heading": heading,
                    "covariance": list(imu.orientation_covariance)},
            "cliff": cliff_events, "bumper": pressed + released}


def motor_power_and_odometry_reset() -> dict[str, float]:
    """How far the Kobuki goes in a simulated second of commands with its motors off, then on; and
    /odom's distance from its origin after commands/reset_odometry."""
    power = rospy.Publisher("/mobile_base/commands/motor_power", MotorPower, queue_size=1, latch=True)
    reset = rospy.Publisher("/mobile_base/commands/reset_odometry", Empty, queue_size=1, latch=True)
    commands = rospy.Publisher("/mobile_base/commands/velocity", Twist, queue_size=1)
    forward = Twist()
    forward.linear.x = 0.2
    state = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)
    moved = {}
    for label, setting in (("off", MotorPower.OFF), ("on", MotorPower.ON)):
        power.publish(MotorPower(state=setting))
        rospy.sleep(0.2)  # simulated time: the latched setting has reached the plugin
        start = state("mobile_base", "world").pose.position
        rate = rospy.Rate(10)
        for _ in range(10):  # a simulated second of 0.2 m/s
            commands.publish(forward)
            rate.sleep()
        end = state("mobile_base", "world").pose.position
        moved[label] = math.hypot(end.x - start.x, end.y - start.y)
    commands.publish(Twist())
    odometry: queue.Queue[Any] = events("/odom", Odometry)
    reset.publish(Empty())
    for _ in range(200):  # /odom at 50 Hz: within 4 s of simulated time its origin is back
        position = odometry.get(timeout=30).pose.pose.position
        if math.hypot(position.x, position.y) < 0.01:
            break
    return {"moved_off": moved["off"], "moved_on": moved["on"], "odom_after_reset": math.hypot(position.x, position.y)}


def main() -> None:
    rospy.init_node("probe", anonymous=True)
    rospy.wait_for_message("/clock", rospy.AnyMsg, timeout=30)  # sim time has begun
    what = sys.argv[1]
    if what == "sensors":
        result = sensors()
    elif what == "drive":
        result = drive(sys.argv[2], float(sys.argv[3]))
    elif what == "kobuki":
        result = kobuki()
    else:
        result = map_while_turning(float(sys.argv[2]))
    print(json.dumps(result), flush=True)


if __name__ == "__main__":
    main()
