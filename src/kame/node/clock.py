"""A Node's ROS time, as roscpp and rospy keep it: the wall clock, or, when the parameter
/use_sim_time is true as the clock starts, the newest /clock message (0 until the first one,
as roscpp). For the programs on an explicit Node (the tf tools, rviz); a kame.client program's
one node keeps rospy's process-wide time in kame.client.clock instead."""

from __future__ import annotations

import time
from collections.abc import Callable

from kame.node.master_proxy import MasterError
from kame.node.node import Node
from kame.rostime import Time


class NodeClock:
    def __init__(self, node: Node, on_change: Callable[[], None] | None = None) -> None:
        """Reads /use_sim_time once, now (the node's master must answer: one that does not means
        the wall clock); under sim time subscribes to /clock and calls `on_change` at each message."""
        self._node = node
        self._on_change = on_change
        self._sim_ns: int | None = None  # None: the wall clock
        self._topic = ""
        if self._use_sim_time():
            from rosgraph_msgs.msg import Clock

            self._sim_ns = 0
            self._topic = node.resolve("/clock")
            node.subscribe(self._topic, Clock._type, Clock._md5sum, Clock._full_text, self._on_clock, queue_size=1)

    def _use_sim_time(self) -> bool:
        try:
            return self._node.master.call("getParam", "/use_sim_time") is True
        except (OSError, MasterError):  # not set, or no master to say
            return False

    def _on_clock(self, frames: list[memoryview], header: dict[str, str]) -> None:
        from rosgraph_msgs.msg import Clock

        clock = Clock._from_buffer(frames[-1]).clock
        self._sim_ns = int(clock.secs) * 1_000_000_000 + int(clock.nsecs)
        if self._on_change is not None:
            self._on_change()

    @property
    def is_sim_time(self) -> bool:
        return self._sim_ns is not None

    def now_ns(self) -> int:
        sim = self._sim_ns
        return time.time_ns() if sim is None else sim

    def now(self) -> Time:
        """ros::Time::now(), for a message's stamp."""
        return Time(*divmod(self.now_ns(), 1_000_000_000))

    def close(self) -> None:
        if self._topic:
            self._node.unsubscribe(self._topic)
            self._topic = ""
