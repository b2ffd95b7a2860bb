"""A ROS client for the 3-D TurtleBot tests, run as its own process with kame's Python: it prints
one JSON line about what it saw, so the test process never holds a node.

    probe.py sensors                 the camera's, depth camera's and scan's first messages, summarised
    probe.py drive TOPIC X_TARGET    publish 0.25 m/s on TOPIC until /odom passes x = X_TARGET
    probe.py map SECONDS             turn in place at 0.6 rad/s for SECONDS of simulated time, and
                                     the first /map made after them
"""

from __future__ import annotations

import json
import math
import sys
from typing import Any

import numpy as np

import rospy
from gazebo_msgs.msg import ModelStates
from geometry_msgs.msg import Twist
from nav_msgs.msg import OccupancyGrid, Odometry
from sensor_msgs.msg import CameraInfo, Image, LaserScan, PointCloud2


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


def main() -> None:
    rospy.init_node("probe", anonymous=True)
    rospy.wait_for_message("/clock", rospy.AnyMsg, timeout=30)  # sim time has begun
    what = sys.argv[1]
    if what == "sensors":
        result = sensors()
    elif what == "drive":
        result = drive(sys.argv[2], float(sys.argv[3]))
    else:
        result = map_while_turning(float(sys.argv[2]))
    print(json.dumps(result), flush=True)


if __name__ == "__main__":
    main()
