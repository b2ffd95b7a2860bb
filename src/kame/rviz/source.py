"""rviz's node: the tf Buffer fed from /tf and /tf_static (kame.tf_ros), one subscription per
topic the displays show, the publishers of the tools and the ROS time that stamps their messages
(kame.node.clock: /clock when /use_sim_time is true as rviz starts, as ros::Time::now()).
Subscriber threads only store bytes: the newest message of a topic (latest wins), or for marker
topics every message up to a bound, and the source's own decoding thread decodes what arrived (a
burst of clouds: the newest only; of marker messages, those a newer one does not supersede) once
the window has taken what it decoded before, and wakes it (`on_ready`), so a 30 Hz 1 MB cloud or
1,000-marker array is never a queue the window falls behind on, and the window's turn only takes
messages."""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from typing import Any

import numpy as np

from kame.catkin import executables
from kame.msg.lookup import message_class
from kame.node.clock import NodeClock
from kame.node.node import Node
from kame.node.topics import serialize_frame
from kame.rviz import backlog
from kame.rviz.scene import pose_matrix
from kame.tf.errors import TransformException
from kame.tf_ros.buffer import Buffer
from kame.tf_ros.node_io import TransformListener

KEPT_PER_TOPIC = 1000  # marker messages waiting for the window; older ones are dropped beyond


class TfFrames:
    """kame.rviz.display.Frames over the Buffer: the newest transform of each frame into the fixed frame."""

    def __init__(self, buffer: Buffer, fixed_frame: str) -> None:
        self.buffer = buffer
        self.fixed_frame = fixed_frame
        self._cache: dict[str, np.ndarray | str] = {}

    def transform(self, frame_id: str) -> np.ndarray | str:
        frame_id = frame_id.lstrip("/")
        if frame_id not in self._cache:  # one lookup per frame and drawn frame
            try:
                found = self.buffer.lookup_transform(self.fixed_frame, frame_id, 0)
                self._cache[frame_id] = pose_matrix(found.transform)
            except TransformException as exc:
                self._cache[frame_id] = f"no transform from {frame_id or '(empty frame_id)'} to {self.fixed_frame}" \
                                        f" ({exc})"
        return self._cache[frame_id]

    def names(self) -> list[str]:
        return sorted(self.buffer.frames())

    def parent(self, frame_id: str) -> str | None:
        return self.buffer.parent_of(frame_id)


# what these carry in big arrays of numbers is read by numpy: decoded straight into arrays over
# the received bytes (a 2,000x2,000 map's int8[] as a tuple of 4 M ints took 75 ms to turn into
# one). A cloud's uint8[] is bytes either way.
NUMPY_TYPES = frozenset({"nav_msgs/OccupancyGrid", "sensor_msgs/LaserScan"})


def decode(cls: type[Any], payload: bytes) -> Any:
    """A message of `cls` from its serialized bytes, as the window gets it (the arrays of
    NUMPY_TYPES as numpy arrays over `payload`)."""
    if cls._type in NUMPY_TYPES:
        return cls().deserialize_numpy(memoryview(payload), np)
    return cls._from_buffer(memoryview(payload))


class RvizSource:
    def __init__(self, node: Node, on_ready: Callable[[], None]) -> None:
        self.node = node
        self.on_ready = on_ready
        # tf's complaints show as display statuses
        self.buffer = Buffer(warn=lambda text: None, error=lambda text: None)
        self.clock = NodeClock(node)
        # ROS time read as each transform arrives: sim time going back (a bag played with --loop
        # --clock) clears the buffer, as rviz's does
        self.listener = TransformListener(node, self.buffer, now=self.clock.now_ns)
        self._lock = threading.Lock()
        self._waiting: dict[str, list[bytes]] = {}  # received, not yet decoded
        self._decoded: dict[str, list[Any]] = {}  # decoded, not yet taken by the window
        self._keep_every: dict[str, bool] = {}
        self._classes: dict[str, type[Any]] = {}
        self._publishers: set[str] = set()
        self._pending = threading.Event()
        self._closing = False
        # decoding (a 2,000-marker array: tens of ms) happens here, never in the window's turn
        self._decoder = threading.Thread(target=self._decode_loop, name="rviz_decode")
        self._decoder.start()

    def frames(self, fixed_frame: str) -> TfFrames:
        return TfFrames(self.buffer, fixed_frame)

    def watch(self, topic: str, type_name: str, keep_every: bool) -> str:
        """Subscribes to `topic` as `type_name`; an empty string, or why it cannot."""
        cls = message_class(type_name)
        if cls is None:
            return f"unknown message type {type_name}"
        topic = self.node.resolve(topic)
        if topic in self._classes:
            if self._classes[topic]._type == type_name:
                self._keep_every[topic] = self._keep_every[topic] or keep_every
                return ""
            return f"{topic} is already shown as {self._classes[topic]._type}"
        self._classes[topic] = cls
        self._keep_every[topic] = keep_every
        self.node.subscribe(topic, cls._type, cls._md5sum, cls._full_text, self._deliverer(topic), queue_size=None)
        return ""

    def unwatch(self, topic: str) -> None:
        topic = self.node.resolve(topic)
        if self._classes.pop(topic, None) is not None:
            self.node.unsubscribe(topic)
        with self._lock:
            self._waiting.pop(topic, None)
            self._decoded.pop(topic, None)

    def watched(self) -> set[str]:
        return set(self._classes)

    def _deliverer(self, topic: str) -> Callable[[list[memoryview], dict[str, str]], None]:
        def deliver(frames: list[memoryview], header: dict[str, str]) -> None:
            if not frames:
                return
            with self._lock:
                if self._keep_every.get(topic):
                    kept = self._waiting.setdefault(topic, [])
                    kept.extend(bytes(frame) for frame in frames)
                    del kept[:-KEPT_PER_TOPIC]
                else:
                    self._waiting[topic] = [bytes(frames[-1])]
            self._pending.set()
        return deliver

    def _decode_loop(self) -> None:
        """Decodes what arrived (the newest of a topic; of marker messages those whose markers
        no newer waiting one replaces) once the window has taken what was decoded before, and
        wakes it: while the window is busy, arrivals wait as bytes, where a backlog is cheap to
        thin out, instead of each being decoded (an array of 1,000 markers: 10-20 ms holding
        the GIL the window needs) and then superseded unseen."""
        while True:
            self._pending.wait()
            self._pending.clear()
            if self._closing:
                return
            with self._lock:
                if any(self._decoded.values()):  # take() wakes this loop again
                    continue
                waiting, self._waiting = self._waiting, {}
            decoded: dict[str, list[Any]] = {}
            for topic, payloads in waiting.items():
                cls = self._classes.get(topic)
                if cls is None:
                    continue
                if len(payloads) > 1 and cls._type in (backlog.MARKER, backlog.MARKER_ARRAY):
                    payloads = backlog.still_needed(payloads, cls._type == backlog.MARKER_ARRAY)
                messages = []
                for payload in payloads:
                    try:
                        messages.append(decode(cls, payload))
                    except Exception:  # a malformed message is dropped; the display keeps the last good one
                        continue
                decoded[topic] = messages
            if not any(decoded.values()):
                continue
            with self._lock:
                for topic, messages in decoded.items():
                    if topic not in self._classes:  # unwatched while it was decoded
                        continue
                    if self._keep_every.get(topic):
                        self._decoded[topic] = messages
                    elif messages:
                        self._decoded[topic] = messages[-1:]
            self.on_ready()

    def take(self) -> dict[str, list[Any]]:
        """Every decoded message waiting, by resolved topic (the newest of a topic; the marker
        messages that change what is shown, in order)."""
        with self._lock:
            taken, self._decoded = self._decoded, {}
            if self._waiting:  # the decoder waited for this
                self._pending.set()
        return taken

    def published_topics(self) -> list[tuple[str, str]]:
        """Every published topic and its type, from the master."""
        return [(str(topic), str(type_name)) for topic, type_name in self.node.master.call("getPublishedTopics", "")]

    def param(self, name: str) -> str | None:
        """A parameter's text (the robot description), None when it is not set or not text."""
        if not name:
            return None
        answer = self.node.master.call_raw("getParam", self.node.resolve(name))
        if not isinstance(answer, list) or len(answer) < 3 or answer[0] != 1 or not isinstance(answer[2], str):
            return None
        return answer[2]

    def find_package(self, name: str) -> str | None:
        """Where package `name` is (ROS_PACKAGE_PATH and kame's own): package:// mesh resources."""
        package = executables.packages(os.environ).get(name)
        return str(package.path) if package is not None else None

    def advertise(self, topic: str, cls: type[Any]) -> str:
        """Publishes `topic` from now on (a tool's first message then finds its subscribers
        connected); the resolved name."""
        topic = self.node.resolve(topic)
        if topic not in self._publishers:
            self.node.advertise(topic, cls._type, cls._md5sum, cls._full_text)
            self._publishers.add(topic)
        return topic

    def publish(self, topic: str, message: Any) -> None:
        topic = self.advertise(topic, type(message))
        self.node.publications[topic].publish_frame(serialize_frame(message))

    def publish_stamped(self, topic: str, message: Any) -> None:
        """A tool's message (2D Pose Estimate, 2D Nav Goal, Publish Point), stamped with ROS time
        now as rviz's tools stamp theirs."""
        message.header.stamp = self.clock.now()
        self.publish(topic, message)

    def close(self) -> None:
        self.clock.close()
        self._closing = True
        self._pending.set()
        self._decoder.join()
        self.listener.unregister()
        for topic in list(self._classes):
            self.unwatch(topic)
        for topic in self._publishers:
            self.node.unadvertise(topic)
        self._publishers.clear()
