"""tf2_ros's buffer_server (`rosrun tf2_ros buffer_server`): a Buffer of ~buffer_size seconds
(default 120) fed by /tf and /tf_static, answering tf2_msgs/LookupTransform goals on the
tf2_buffer_server action; and BufferServer, the class behind it (tf2_ros.BufferServer).

A goal waits, woken by arriving transforms, up to its timeout, then is answered with the
transform or tf2's error code and text (always SUCCEEDED, as tf2_ros's server does). Each
waiting goal has a thread the server owns and joins in stop()."""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Sequence
from typing import Any

from kame.client import clock, core, process
from kame.client.action.action_server import ActionServer
from kame.client.action.server_goal_handle import ServerGoalHandle
from kame.rostime import Duration
from kame.tf.errors import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TimeoutException,
    TransformException,
)
from kame.tf_ros.buffer import Buffer
from kame.tf_ros.node_io import TransformListener
from tf2_msgs.msg import LookupTransformAction, LookupTransformResult, TF2Error

CODES = ((LookupException, TF2Error.LOOKUP_ERROR), (ConnectivityException, TF2Error.CONNECTIVITY_ERROR),
         (ExtrapolationException, TF2Error.EXTRAPOLATION_ERROR),
         (InvalidArgumentException, TF2Error.INVALID_ARGUMENT_ERROR), (TimeoutException, TF2Error.TIMEOUT_ERROR))


class BufferServer:
    def __init__(self, buffer: Any, ns: str, auto_start: bool = True) -> None:
        self.buffer = buffer
        self._lock = threading.Lock()
        self._waiters: set[threading.Thread] = set()
        self._stopped = threading.Event()
        self.server = ActionServer(ns, LookupTransformAction, self._on_goal, auto_start=False)
        if auto_start:
            self.start()

    def start(self) -> None:
        self.server.start()

    def stop(self) -> None:
        self._stopped.set()
        self.buffer.wake()
        with self._lock:
            waiters = list(self._waiters)
        for thread in waiters:
            thread.join()

    def _on_goal(self, handle: ServerGoalHandle) -> None:
        handle.set_accepted()
        thread = threading.Thread(target=self._answer, args=(handle,), name="tf2-buffer-server-goal", daemon=True)
        with self._lock:
            self._waiters.add(thread)
        thread.start()

    def _answer(self, handle: ServerGoalHandle) -> None:
        try:
            goal = handle.get_goal()
            result = LookupTransformResult()
            fixed = goal.fixed_frame if goal.advanced else ""
            self.buffer.wait_for(goal.target_frame, goal.source_frame, goal.source_time, goal.timeout, self._stopped,
                                 goal.target_time, fixed)
            try:
                if goal.advanced:
                    result.transform = self.buffer.lookup_transform_full(
                        goal.target_frame, goal.target_time, goal.source_frame, goal.source_time, goal.fixed_frame)
                else:
                    result.transform = self.buffer.lookup_transform(goal.target_frame, goal.source_frame,
                                                                    goal.source_time)
            except TransformException as exc:
                result.error.error = next((code for kind, code in CODES if isinstance(exc, kind)),
                                          TF2Error.TRANSFORM_ERROR)
                result.error.error_string = str(exc)
            if not self._stopped.is_set():
                handle.set_succeeded(result)
        finally:
            with self._lock:
                self._waiters.discard(threading.current_thread())


def _now_ns() -> int:
    """ROS time in ns: the node's clock (/clock under sim time), else the wall clock."""
    return clock.get_rostime().to_nsec() if clock.is_rostime_initialized() else time.time_ns()


def main(argv: Sequence[str] | None = None) -> int:
    process.init_node("tf2_buffer_server", argv=list(sys.argv if argv is None else argv))
    buffer = Buffer(Duration.from_sec(float(process.get_param("~buffer_size", 120.0))))
    node = core.get_node()
    assert node is not None  # init_node made it
    TransformListener(node, buffer, now=_now_ns)
    server = BufferServer(buffer, "tf2_buffer_server")
    process.spin()
    server.stop()
    return 0


if __name__ == "__main__":
    sys.exit(main())
