"""static_transform_publisher, both forms.

tf2_ros's (`rosrun tf2_ros static_transform_publisher x y z yaw pitch roll frame child`, or
`x y z qx qy qz qw frame child`, or `/param_name` holding a TransformStamped-shaped dict):
publishes the transform once on the latched /tf_static and spins.
tf's (`rosrun tf static_transform_publisher ... frame child period_ms`): republishes the
transform on /tf every period, stamped one period into the future, as tf's program does.
Usage errors print the programs' usage and exit 255.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence
from typing import Any

from kame.cli._console import console
from kame.cli._tf import start_node
from kame.tf import rotation
from kame.tf.transformations import quaternion_from_euler

TF2_USAGE = """A command line utility for manually sending a transform.
Usage: static_transform_publisher x y z qx qy qz qw frame_id child_frame_id 
OR 
Usage: static_transform_publisher x y z yaw pitch roll frame_id child_frame_id 
OR 
Usage: static_transform_publisher /param_name 

This transform is the transform of the coordinate frame from frame_id into the coordinate frame 
of the child_frame_id.  
"""  # noqa: W291 -- the program's own trailing spaces

TF_USAGE = """A command line utility for manually sending a transform.
It will periodicaly republish the given transform. 
Usage: static_transform_publisher x y z yaw pitch roll frame_id child_frame_id  period(milliseconds) 
OR 
Usage: static_transform_publisher x y z qx qy qz qw frame_id child_frame_id  period(milliseconds) 

This transform is the transform of the coordinate frame from frame_id into the coordinate frame 
of the child_frame_id.  
"""  # noqa: W291

WRONG_COUNT = "static_transform_publisher exited due to not having the right number of arguments"


def _transform(parent: str, child: str, stamp_ns: int, translation: Sequence[float],
               quaternion: Sequence[float]) -> Any:
    from geometry_msgs.msg import TransformStamped
    from kame.rostime import Time

    msg = TransformStamped()
    msg.header.frame_id, msg.child_frame_id = parent, child
    msg.header.stamp = Time(stamp_ns // 1_000_000_000, stamp_ns % 1_000_000_000)
    t, r = msg.transform.translation, msg.transform.rotation
    t.x, t.y, t.z = (float(v) for v in translation)
    r.x, r.y, r.z, r.w = (float(v) for v in quaternion)
    return msg


def _numbers(words: Sequence[str]) -> list[float]:
    """atof: what does not parse is 0, as the C programs read their arguments."""
    out = []
    for word in words:
        try:
            out.append(float(word))
        except ValueError:
            out.append(0.0)
    return out


def _pose(args: Sequence[str]) -> tuple[list[float], tuple[float, float, float, float], str, str] | None:
    if len(args) == 9:
        values = _numbers(args[:7])
        quaternion = (values[3], values[4], values[5], values[6])
    elif len(args) == 8:
        values = _numbers(args[:6])
        yaw, pitch, roll = values[3:6]
        q = quaternion_from_euler(roll, pitch, yaw)
        quaternion = (float(q[0]), float(q[1]), float(q[2]), float(q[3]))
    else:
        return None
    return values[:3], quaternion, args[-2], args[-1]


def _from_param(tool: Any, name: str) -> tuple[list[float], tuple[float, float, float, float], str, str] | None:
    console("INFO", f"Looking for TF in parameter: {name}")
    try:
        data = tool.node.master.call("getParam", tool.node.resolve(name))
        t, r = data["transform"]["translation"], data["transform"]["rotation"]
        return ([float(t[k]) for k in "xyz"], (float(r["x"]), float(r["y"]), float(r["z"]), float(r["w"])),
                str(data["header"]["frame_id"]), str(data["child_frame_id"]))
    except Exception:
        console("FATAL", f"Could not read TF from parameter server: {name}")
        return None


def main_tf2(argv: Sequence[str] | None = None) -> int:
    """tf2_ros's static_transform_publisher: once, latched on /tf_static."""
    from kame.tf_ros.node_io import StaticTransformBroadcaster

    tool, args = start_node(sys.argv[1:] if argv is None else argv, "static_transform_publisher")
    try:
        pose = _pose(args) if len(args) != 1 else None
        if pose is None and len(args) != 1:
            print(TF2_USAGE, end="", flush=True)
            console("ERROR", WRONG_COUNT)
            return 255
        if not tool.wait_for_master():
            return 0
        if pose is None:
            pose = _from_param(tool, args[0])
            if pose is None:
                return 255
        translation, quaternion, parent, child = pose
        if parent == child:
            console("FATAL", f"target_frame and source frame are the same ({parent}, {child}) this cannot work")
            return 1
        StaticTransformBroadcaster(tool.node).send_transform(
            _transform(parent, child, tool.now_ns(), translation, quaternion))
        console("INFO", f"Spinning until killed publishing {parent} to {child}")
        tool.stop.wait()
        return 0
    finally:
        tool.node.shutdown("static_transform_publisher exiting")


def main_tf(argv: Sequence[str] | None = None) -> int:
    """tf's static_transform_publisher: every period on /tf, stamped a period ahead."""
    from kame.tf_ros.node_io import TransformBroadcaster

    tool, args = start_node(sys.argv[1:] if argv is None else argv, "static_transform_publisher")
    try:
        pose = _pose(args[:-1]) if args else None
        if pose is None:
            print(TF_USAGE, end="", flush=True)
            console("ERROR", WRONG_COUNT)
            return 255
        translation, quaternion, parent, child = pose
        # tf's Transform keeps a rotation matrix: what it sends is the normalized quaternion
        quaternion = rotation.from_matrix(rotation.to_matrix(quaternion)) if any(quaternion) else quaternion
        period = _numbers(args[-1:])[0] / 1000.0
        if parent == child:
            console("FATAL", f"target_frame and source frame are the same ({parent}, {child}) this cannot work")
        if not tool.wait_for_master():
            return 0
        broadcaster = TransformBroadcaster(tool.node)
        ahead = round(period * 1e9) if math.isfinite(period) and period > 0 else 0
        while True:
            broadcaster.send_transform(_transform(parent, child, tool.now_ns() + ahead, translation, quaternion))
            if not tool.sleep_ns(ahead) or tool.stop.is_set():
                return 0
    finally:
        tool.node.shutdown("static_transform_publisher exiting")


if __name__ == "__main__":
    sys.exit(main_tf2())
