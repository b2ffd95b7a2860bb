"""What kame's tf programs share (static_transform_publisher, tf_echo, tf2_echo, view_frames,
tf_monitor): a node named as roscpp names an anonymous node, roscpp-style console lines, and a
Buffer fed by /tf and /tf_static."""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from typing import Any

from kame import names
from kame.cli._console import console
from kame.cli._node import ToolNode
from kame.node.clock import NodeClock
from kame.tf_ros.buffer import Buffer
from kame.tf_ros.node_io import TransformListener


class TfTool(ToolNode):
    """A ToolNode that, once the master answers, sets its `_name:=value` arguments as private
    parameters, typed as roscpp types them (int, double, bool, else string), and keeps ROS
    time: the wall clock, or /clock when /use_sim_time is true (a bag played with --clock)."""

    def __init__(self, special: dict[str, str], default_name: str, remappings: dict[str, str],
                 params: dict[str, str]) -> None:
        super().__init__(special, default_name, remappings)
        self.params = params
        self.clock: NodeClock | None = None  # once the master answers

    def wait_for_master(self) -> bool:
        if not super().wait_for_master():
            return False
        for key, text in self.params.items():
            self.node.master.call("setParam", self.node.resolve(key), roscpp_value(text))
        self.clock = NodeClock(self.node, on_change=self.notify)
        return True

    def now_ns(self) -> int:
        """ROS time in ns (0 under sim time until the first /clock, as roscpp); the wall clock
        until the master answers."""
        return time.time_ns() if self.clock is None else self.clock.now_ns()

    def sleep_ns(self, duration: int) -> bool:
        """ros::Duration::sleep: `duration` of ROS time (under sim time, until /clock has moved
        that far); False when the tool was stopped first."""
        if self.clock is None or not self.clock.is_sim_time:
            return not self.stop.wait(duration / 1e9)
        until = self.now_ns() + duration
        return self.wait_until(lambda: self.now_ns() >= until)


def roscpp_value(text: str) -> Any:
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    if text.lower() in ("true", "false"):
        return text.lower() == "true"
    return text


def start_node(argv: Sequence[str], default_name: str, anonymous: bool = True) -> tuple[TfTool, list[str]]:
    """The program's node (not yet talking to the master) and its own arguments."""
    ros = names.parse_args(argv)
    special = dict(ros.special)
    if anonymous and "name" not in special:
        special["name"] = f"{default_name}_{time.time_ns()}"  # roscpp's AnonymousName
    return TfTool(special, default_name, dict(ros.remappings), dict(ros.params)), ros.argv


def listening_buffer(tool: TfTool, on_message: Callable[[Any, str, bool], None] | None = None,
                     ) -> tuple[Buffer, TransformListener]:
    """A Buffer fed from /tf and /tf_static; `on_message` also sees each message."""
    buffer = Buffer(warn=lambda text: console("WARN", text), error=lambda text: console("ERROR", text))
    return buffer, TransformListener(tool.node, buffer, now=tool.now_ns, on_message=on_message)


def wall_seconds_text(ns: int) -> str:
    """ros::Time's `<<`: seconds.nanoseconds, nine digits."""
    return f"{ns // 1_000_000_000}.{ns % 1_000_000_000:09d}"
