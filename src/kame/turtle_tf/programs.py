"""turtle_tf's and turtle_tf2's C++ demo programs (turtle_tf_broadcaster, turtle_tf_listener,
turtle_tf2_broadcaster, turtle_tf2_listener); on the wire tf and tf2 are the same.

`*_broadcaster /turtle1` (or the `~turtle` parameter, as the launch files set it): each
turtlesim/Pose on `turtle1/pose` becomes the transform world -> turtle1 (x, y, 0; yaw theta)
stamped now.
`*_listener`: waits for `spawn`, calls it with the request's defaults (turtlesim names the
turtle `turtle2`), then ten times a second steers turtle2 toward turtle1 with the tutorial's
gains: angular.z = 4 atan2(y, x), linear.x = 0.5 sqrt(x^2 + y^2), (x, y) being turtle1 in
turtle2's frame. A failed lookup is logged and, a second later, a zero command sent, as the
C++ programs do.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence

from kame.cli._console import console
from kame.cli._node import ToolNode
from kame.cli._tf import listening_buffer, start_node
from kame.node.services import ServiceError, probe_service
from kame.node.topics import serialize_frame, serialize_payload
from kame.tf import errors
from kame.tf.transformations import quaternion_from_euler
from kame.tf_ros.node_io import TransformBroadcaster


def tf2_broadcaster_main(argv: Sequence[str] | None = None) -> int:
    return broadcaster_main(argv, "my_tf2_broadcaster")


def tf2_listener_main(argv: Sequence[str] | None = None) -> int:
    return listener_main(argv, "my_tf2_listener")


def broadcaster_main(argv: Sequence[str] | None = None, name: str = "my_tf_broadcaster") -> int:
    from geometry_msgs.msg import TransformStamped
    from kame.rostime import Time
    from turtlesim.msg import Pose

    tool, args = start_node(sys.argv[1:] if argv is None else argv, name, anonymous=False)
    try:
        if not tool.wait_for_master():
            return 0
        node = tool.node
        turtle = args[0] if len(args) == 1 else _private_param(tool, "turtle")
        if not turtle:
            console("ERROR", "need turtle name as argument")
            return 255
        broadcaster = TransformBroadcaster(node)

        def on_pose(frames: list[memoryview], header: dict[str, str]) -> None:
            for frame in frames:
                pose = Pose._from_buffer(frame)
                t = TransformStamped()
                now = tool.now_ns()
                t.header.stamp = Time(now // 1_000_000_000, now % 1_000_000_000)
                t.header.frame_id, t.child_frame_id = "world", turtle
                t.transform.translation.x, t.transform.translation.y = pose.x, pose.y
                q = quaternion_from_euler(0.0, 0.0, pose.theta)
                r = t.transform.rotation
                r.x, r.y, r.z, r.w = (float(v) for v in q)
                broadcaster.send_transform(t)

        node.subscribe(node.resolve(f"{turtle}/pose"), Pose._type, Pose._md5sum, Pose._full_text, on_pose,
                       queue_size=10)
        tool.stop.wait()
        return 0
    finally:
        tool.node.shutdown("turtle_tf_broadcaster exiting")


def steering(x: float, y: float) -> tuple[float, float]:
    """(linear.x, angular.z) toward a target at (x, y) in the turtle's frame: the tutorial's gains."""
    return 0.5 * math.sqrt(x ** 2 + y ** 2), 4.0 * math.atan2(y, x)


def listener_main(argv: Sequence[str] | None = None, name: str = "my_tf_listener") -> int:
    from geometry_msgs.msg import Twist
    from turtlesim.srv import Spawn, SpawnRequest, SpawnResponse

    tool, _ = start_node(sys.argv[1:] if argv is None else argv, name, anonymous=False)
    node = tool.node
    try:
        if not tool.wait_for_master():
            return 0
        spawn = node.resolve("spawn")
        while not _service_ready(tool, spawn):
            if tool.stop.wait(0.1):  # ROS 1 has no "service appeared" event: roscpp polls too
                return 0
        client = node.service_client(spawn, Spawn._type, Spawn._md5sum)
        try:
            SpawnResponse().deserialize(client.call(serialize_payload(SpawnRequest())))
        except ServiceError as exc:
            console("ERROR", f"Failed to call service spawn: {exc}")
        publication = node.advertise(node.resolve("turtle2/cmd_vel"), Twist._type, Twist._md5sum, Twist._full_text,
                                     queue_size=10)
        buffer, _ = listening_buffer(tool)
        while not tool.stop.is_set():
            x = y = 0.0
            try:
                found = buffer.lookup_transform("turtle2", "turtle1", 0).transform.translation
                x, y = found.x, found.y
            except errors.TransformException as exc:
                console("ERROR", str(exc))
                if tool.stop.wait(1.0):
                    break
            twist = Twist()
            twist.linear.x, twist.angular.z = steering(x, y)
            publication.publish_frame(serialize_frame(twist))
            tool.stop.wait(0.1)
        return 0
    finally:
        node.shutdown("turtle_tf_listener exiting")


def _private_param(tool: ToolNode, name: str) -> str:
    try:
        return str(tool.node.master.call("getParam", tool.node.resolve("~" + name)))
    except Exception:
        return ""


def _service_ready(tool: ToolNode, name: str) -> bool:
    node = tool.node
    try:
        probe_service(node.master, node.name, name, 2.0)
        return True
    except Exception:
        return False
