"""interactive_markers.interactive_marker_server: the InteractiveMarkerServer of ROS 1 (1.12)
on rospy: <topic_ns>/update (changes at applyChanges, a KEEP_ALIVE every 0.5 s),
<topic_ns>/update_full (latched: every marker) and <topic_ns>/feedback (the clients' drags,
clicks and menu choices, handed to the markers' callbacks). What it sends and does is
kame.interactive_markers.server_state; this holds the node's side and a lock."""

from __future__ import annotations

import time
from collections.abc import Callable
from threading import Lock
from typing import Any

import rospy
from kame.interactive_markers.server_state import DEFAULT_FEEDBACK_CB, ServerState
from std_msgs.msg import Header
from visualization_msgs.msg import (
    InteractiveMarker,
    InteractiveMarkerFeedback,
    InteractiveMarkerInit,
    InteractiveMarkerPose,
    InteractiveMarkerUpdate,
)

KEEP_ALIVE_SECONDS = 0.5


class InteractiveMarkerServer:
    DEFAULT_FEEDBACK_CB = DEFAULT_FEEDBACK_CB

    def __init__(self, topic_ns: str, server_id: str | None = None, q_size: int = 100) -> None:
        self.topic_ns = topic_ns
        self.server_id = rospy.get_name() + (server_id or "")
        self._state = ServerState(self.server_id)
        self._lock = Lock()
        self.init_pub = rospy.Publisher(topic_ns + "/update_full", InteractiveMarkerInit, latch=True, queue_size=100)
        self.update_pub = rospy.Publisher(topic_ns + "/update", InteractiveMarkerUpdate, queue_size=100)
        self.feedback_sub = rospy.Subscriber(topic_ns + "/feedback", InteractiveMarkerFeedback, self.processFeedback,
                                             queue_size=q_size)
        self.keep_alive_timer: rospy.Timer | None = rospy.Timer(rospy.Duration(KEEP_ALIVE_SECONDS), self.keepAlive)
        self.publishInit()

    @property
    def seq_num(self) -> int:
        return self._state.seq_num

    def insert(self, marker: Any, feedback_cb: Callable[[Any], None] | None = None,
               feedback_type: int = DEFAULT_FEEDBACK_CB) -> None:
        with self._lock:
            self._state.insert(marker, feedback_cb, feedback_type)

    def setPose(self, name: str, pose: Any, header: Any = None) -> bool:
        with self._lock:
            return self._state.set_pose(name, pose, header if header is not None else Header())

    def erase(self, name: str) -> bool:
        with self._lock:
            return self._state.erase(name)

    def clear(self) -> None:
        with self._lock:
            self._state.clear()

    def setCallback(self, name: str, feedback_cb: Callable[[Any], None] | None,
                    feedback_type: int = DEFAULT_FEEDBACK_CB) -> bool:
        with self._lock:
            return self._state.set_callback(name, feedback_cb, feedback_type)

    def applyChanges(self) -> None:
        with self._lock:
            update = self._state.apply_changes()
            init = self._state.init_message() if update is not None else None
        if update is not None:
            self.update_pub.publish(update)
            self.init_pub.publish(init)

    def get(self, name: str) -> Any:
        with self._lock:
            return self._state.get(name)

    def empty(self) -> bool:
        return self.size() == 0

    def size(self) -> int:
        with self._lock:
            return self._state.size()

    def processFeedback(self, feedback: Any) -> None:
        with self._lock:
            callback = self._state.feedback(feedback, time.monotonic())
        if callback is not None:
            callback(feedback)

    def keepAlive(self, event: Any = None) -> None:
        with self._lock:
            message = self._state.keep_alive()
        self.update_pub.publish(message)

    def publishInit(self) -> None:
        with self._lock:
            init = self._state.init_message()
        self.init_pub.publish(init)

    def shutdown(self) -> None:
        """Erases every marker for the clients and leaves the topics (C++'s destructor)."""
        if self.keep_alive_timer is None:
            return
        self.keep_alive_timer.shutdown()
        self.keep_alive_timer = None
        self.clear()
        self.applyChanges()
        self.feedback_sub.unregister()
        self.update_pub.unregister()
        self.init_pub.unregister()


# what `from interactive_markers.interactive_marker_server import *` gives in ROS (its module has no
# __all__), which scripts written for it may use: its imports, but for ROS's private helper classes
__all__ = ["Header", "InteractiveMarker", "InteractiveMarkerFeedback", "InteractiveMarkerInit", "InteractiveMarkerPose",
           "InteractiveMarkerServer", "InteractiveMarkerUpdate", "Lock", "rospy"]
