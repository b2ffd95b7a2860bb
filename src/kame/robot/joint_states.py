"""joint_state_publisher's publishing half: every moving joint's position on `joint_states`
`~rate` (10) times a second, the positions changed by `~source_list` topics or by the sliders'
window (kame.robot.sliders) under `lock`; and the node's parameters and clock as the robot
programs read them."""

from __future__ import annotations

import threading
from collections.abc import Callable, Mapping
from typing import Any

from kame.cli._node import ToolNode
from kame.node.topics import serialize_frame
from kame.robot.model import JointPositions, RobotTree
from kame.rostime import Time


def ros_param(tool: ToolNode, name: str, default: Any) -> Any:
    """The parameter `name` (resolved in the node's namespace), or `default` when it is not set."""
    try:
        return tool.node.master.call("getParam", tool.node.resolve(name))
    except Exception:  # not set
        return default


def ros_now(tool: Any) -> Time:
    """The node's time now: /clock's under /use_sim_time."""
    ns = tool.now_ns()
    return Time(ns // 1_000_000_000, ns % 1_000_000_000)


class JointStatePublisher:
    """The publishing half of joint_state_publisher; the window (if any) changes `positions`
    under `lock`."""

    def __init__(self, tool: Any, tree: RobotTree) -> None:
        from sensor_msgs.msg import JointState

        self.tool = tool
        self.lock = threading.Lock()
        zeros = ros_param(tool, "~zeros", {})
        self.positions = JointPositions(tree, zeros if isinstance(zeros, Mapping) else {})
        rate = float(ros_param(tool, "~rate", 10.0))
        self.period = 1.0 / rate if rate > 0 else 0.1
        self.message = JointState
        node = tool.node
        self.publication = node.advertise(node.resolve("joint_states"), JointState._type, JointState._md5sum,
                                          JointState._full_text, queue_size=5)
        sources = ros_param(tool, "~source_list", [])
        for topic in sources if isinstance(sources, list) else []:
            node.subscribe(node.resolve(str(topic)), JointState._type, JointState._md5sum, JointState._full_text,
                           self._on_source, queue_size=1)

    def _on_source(self, frames: list[memoryview], header: dict[str, str]) -> None:
        message = self.message._from_buffer(frames[-1])
        with self.lock:
            self.positions.update(list(message.name), list(message.position))

    def publish(self) -> None:
        with self.lock:
            names, positions = self.positions.names_and_positions()
        message = self.message()
        message.header.stamp = ros_now(self.tool)
        message.name, message.position = names, positions
        self.publication.publish_frame(serialize_frame(message))

    def run(self, stopped: Callable[[float], bool]) -> None:
        """Publish every period until `stopped(timeout)` says the program ends."""
        while True:
            self.publish()
            if stopped(self.period):
                return
