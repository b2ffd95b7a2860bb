"""robot_state_publisher and joint_state_publisher, as ROS runs them.

robot_state_publisher: reads `robot_description` (searched upward from the node's namespace),
publishes the fixed joints once on the latched /tf_static, and for each sensor_msgs/JointState
on `joint_states` the moving joints it names (and their mimic joints) on /tf, stamped with the
message's stamp, at most `~publish_frequency` (50) times a second per joint; `~tf_prefix`
prefixes every frame. `rosrun robot_state_publisher state_publisher` is the same program.
joint_state_publisher: publishes every moving joint's position on `joint_states` `~rate` (10)
times a second: the free joints' own (0, or as the sliders of joint_state_publisher_gui set
them), mimic joints following; `~zeros` gives other starting positions and `~source_list`
topics (JointState) set the positions of the joints they name.
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Sequence
from typing import Any

from kame.cli._console import console
from kame.cli._node import ToolNode
from kame.cli._tf import start_node
from kame.robot.joint_states import JointStatePublisher, ros_now, ros_param
from kame.robot.model import RobotTree, Transform
from kame.rostime import Time
from kame.tf_ros.node_io import StaticTransformBroadcaster, TransformBroadcaster


def _description(tool: ToolNode, key: str = "robot_description") -> str | None:
    code, _, found = tool.node.master.call_raw("searchParam", key)
    if code != 1:
        return None
    text = ros_param(tool, str(found), None)
    return text if isinstance(text, str) else None


def _load_tree(tool: ToolNode) -> RobotTree | None:
    text = _description(tool)
    if text is None:
        console("ERROR", "Could not find parameter robot_description on parameter server")
        return None
    try:
        return RobotTree(text)
    except ValueError as exc:
        console("ERROR", f"Failed to extract kdl tree from xml robot description: {exc}")
        return None


def _stamped(transform: Transform, stamp: Time, prefix: str) -> Any:
    from geometry_msgs.msg import TransformStamped

    parent, child, translation, quaternion = transform
    msg = TransformStamped()
    msg.header.stamp = stamp
    msg.header.frame_id = f"{prefix}/{parent}" if prefix else parent
    msg.child_frame_id = f"{prefix}/{child}" if prefix else child
    t, r = msg.transform.translation, msg.transform.rotation
    t.x, t.y, t.z = translation
    r.x, r.y, r.z, r.w = quaternion
    return msg


def state_publisher_main(argv: Sequence[str] | None = None) -> int:
    from sensor_msgs.msg import JointState

    tool, _ = start_node(sys.argv[1:] if argv is None else argv, "robot_state_publisher", anonymous=False)
    node = tool.node
    try:
        if not tool.wait_for_master():
            return 0
        tree = _load_tree(tool)
        if tree is None:
            return 1
        prefix = str(ros_param(tool, "~tf_prefix", "")).strip("/")
        frequency = float(ros_param(tool, "~publish_frequency", 50.0))
        ignore_timestamp = bool(ros_param(tool, "~ignore_timestamp", False))
        period_ns = int(1e9 / frequency) if frequency > 0 else 0
        if bool(ros_param(tool, "~use_tf_static", True)):
            StaticTransformBroadcaster(node).send_transform(
                [_stamped(t, ros_now(tool), prefix) for t in tree.static_transforms()])
        broadcaster = TransformBroadcaster(node)
        last_published: dict[str, int] = {}
        lock = threading.Lock()

        def on_joint_states(frames: list[memoryview], header: dict[str, str]) -> None:
            for frame in frames:
                message = JointState._from_buffer(frame)
                if len(message.name) != len(message.position):
                    console("ERROR", "Robot state publisher ignored an invalid JointState message")
                    continue
                stamp = ros_now(tool) if ignore_timestamp else message.header.stamp
                stamp_ns = stamp.secs * 1_000_000_000 + stamp.nsecs
                with lock:  # several publishers' callbacks may run at once
                    due = {name: position for name, position in zip(message.name, message.position, strict=True)
                           if ignore_timestamp or stamp_ns >= last_published.get(name, -period_ns) + period_ns}
                    for name in due:
                        last_published[name] = stamp_ns
                transforms = tree.moving_transforms(due)
                if transforms:
                    broadcaster.send_transform([_stamped(t, stamp, prefix) for t in transforms])

        node.subscribe(node.resolve("joint_states"), JointState._type, JointState._md5sum, JointState._full_text,
                       on_joint_states, queue_size=100)
        tool.stop.wait()
        return 0
    finally:
        node.shutdown("robot_state_publisher exiting")


def deprecated_state_publisher_main(argv: Sequence[str] | None = None) -> int:
    console("WARN", "The 'state_publisher' executable is deprecated. Please use 'robot_state_publisher' instead")
    return state_publisher_main(argv)


def joint_state_publisher_main(argv: Sequence[str] | None = None, window: bool = False) -> int:
    tool, _ = start_node(sys.argv[1:] if argv is None else argv, "joint_state_publisher", anonymous=False)
    node = tool.node
    try:
        if not tool.wait_for_master():
            return 0
        tree = _load_tree(tool)
        if tree is None:
            return 1
        publisher = JointStatePublisher(tool, tree)
        if not window and bool(ros_param(tool, "~use_gui", False)):
            console("WARN", "The 'use_gui' parameter was specified, which is deprecated.  We'll attempt to find and "
                            "run the GUI, but if this fails you should install the 'joint_state_publisher_gui' "
                            "package instead and run that.  This backwards compatibility option will be removed in "
                            "Noetic.")
            window = True
        if window:
            from kame.robot.sliders import run_window

            worker = threading.Thread(target=publisher.run, args=(tool.stop.wait,), name="joint_states")
            worker.start()
            try:
                return run_window(publisher, tool.stop)
            finally:
                tool.request_stop()
                worker.join()
        publisher.run(tool.stop.wait)
        return 0
    finally:
        node.shutdown("joint_state_publisher exiting")


def joint_state_publisher_gui_main(argv: Sequence[str] | None = None) -> int:
    return joint_state_publisher_main(argv, window=True)
