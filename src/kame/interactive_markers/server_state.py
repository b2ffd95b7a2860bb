"""The bookkeeping of interactive_markers' InteractiveMarkerServer (ROS 1, 1.12), without I/O:
changes (insert, setPose, erase) wait until applyChanges, which turns them into one
InteractiveMarkerUpdate with the next sequence number; update_full's InteractiveMarkerInit is
the whole state under that number; a KEEP_ALIVE repeats it; a client's feedback moves the
marker (a POSE_UPDATE waiting for the next applyChanges) and picks the callback to call.
The node (sockets, the keep-alive timer, the lock) is the interactive_markers package."""

from __future__ import annotations

import copy
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from visualization_msgs.msg import (
    InteractiveMarkerFeedback,
    InteractiveMarkerInit,
    InteractiveMarkerPose,
    InteractiveMarkerUpdate,
)

DEFAULT_FEEDBACK_CB = 255  # the feedback type meaning "any type without a callback of its own"
FULL_UPDATE, POSE_UPDATE, ERASE = range(3)
CLIENT_CONFLICT_SECONDS = 1.0  # feedback from a second client this soon after the first's is ignored

Callback = Callable[[Any], None]


@dataclass
class Callbacks:
    default: Callback | None = None
    by_type: dict[int, Callback] = field(default_factory=dict)

    def set(self, callback: Callback | None, feedback_type: int) -> None:
        if feedback_type == DEFAULT_FEEDBACK_CB:
            self.default = callback
        elif callback is not None:
            self.by_type[feedback_type] = callback
        else:  # as ROS: an empty callback unsets the type's own
            self.by_type.pop(feedback_type, None)

    def for_type(self, feedback_type: int) -> Callback | None:
        return self.by_type.get(feedback_type, self.default)


@dataclass
class Published:
    marker: Any  # visualization_msgs/InteractiveMarker as clients have it
    callbacks: Callbacks
    last_feedback: float = -math.inf
    last_client_id: str = ""


@dataclass
class Pending:
    kind: int
    marker: Any  # FULL_UPDATE: the marker; POSE_UPDATE: carries the new pose and header
    callbacks: Callbacks = field(default_factory=Callbacks)


class ServerState:
    def __init__(self, server_id: str) -> None:
        self.server_id = server_id
        self.seq_num = 0
        self.published: dict[str, Published] = {}
        self.pending: dict[str, Pending] = {}

    def insert(self, marker: Any, feedback_cb: Callback | None = None,
               feedback_type: int = DEFAULT_FEEDBACK_CB) -> None:
        """Adds or replaces `marker` at the next applyChanges; a callback given replaces the type's now."""
        pending = self.pending.get(marker.name)
        if pending is None:
            pending = self.pending[marker.name] = Pending(FULL_UPDATE, marker)
        pending.kind, pending.marker = FULL_UPDATE, marker
        if feedback_cb is not None:
            self.set_callback(marker.name, feedback_cb, feedback_type)

    def set_pose(self, name: str, pose: Any, header: Any = None) -> bool:
        """Moves marker `name` at the next applyChanges (an empty header: keep its frame)."""
        published, pending = self.published.get(name), self.pending.get(name)
        if published is None and pending is None:
            return False
        if header is None or not header.frame_id:
            header = (pending.marker if pending is not None and pending.kind == FULL_UPDATE
                      else published.marker if published is not None else pending.marker).header  # type: ignore[union-attr]
        self._move(name, pose, header)
        return True

    def _move(self, name: str, pose: Any, header: Any) -> None:
        pending = self.pending.get(name)
        if pending is None or pending.kind == ERASE:
            carrier = copy.copy(self.published[name].marker) if name in self.published else None
            pending = self.pending[name] = Pending(POSE_UPDATE, carrier)
        elif pending.kind == POSE_UPDATE:
            pending.marker = copy.copy(pending.marker)
        pending.marker.pose, pending.marker.header = pose, header

    def erase(self, name: str) -> bool:
        if name in self.pending:
            self.pending[name].kind = ERASE
            return True
        if name in self.published:
            self.pending[name] = Pending(ERASE, self.published[name].marker)
            return True
        return False

    def clear(self) -> None:
        self.pending = {}
        for name in self.published:
            self.erase(name)

    def set_callback(self, name: str, feedback_cb: Callback | None,
                     feedback_type: int = DEFAULT_FEEDBACK_CB) -> bool:
        published, pending = self.published.get(name), self.pending.get(name)
        if published is None and pending is None:
            return False
        for holder in (published, pending):
            if holder is not None:
                holder.callbacks.set(feedback_cb, feedback_type)
        return True

    def get(self, name: str) -> Any:
        """The marker as it will be after the next applyChanges (None: none or erased)."""
        pending, published = self.pending.get(name), self.published.get(name)
        if pending is None:
            return published.marker if published is not None else None
        if pending.kind == FULL_UPDATE:
            return pending.marker
        if pending.kind == POSE_UPDATE and published is not None:
            marker = copy.copy(published.marker)
            marker.pose = pending.marker.pose
            return marker
        return None

    def size(self) -> int:
        return len(self.published)

    def apply_changes(self) -> Any:
        """The InteractiveMarkerUpdate of what changed (None: nothing to send); the sequence
        number counts it."""
        if not self.pending:
            return None
        update = InteractiveMarkerUpdate(type=InteractiveMarkerUpdate.UPDATE)
        for name, pending in self.pending.items():
            published = self.published.get(name)
            if pending.kind == FULL_UPDATE:
                if published is None:
                    published = self.published[name] = Published(pending.marker, pending.callbacks)
                published.marker = pending.marker
                update.markers.append(pending.marker)
            elif pending.kind == POSE_UPDATE and published is not None:
                published.marker = copy.copy(published.marker)
                published.marker.pose, published.marker.header = pending.marker.pose, pending.marker.header
                update.poses.append(InteractiveMarkerPose(header=published.marker.header, pose=published.marker.pose,
                                                          name=name))
            elif pending.kind == ERASE and published is not None:
                del self.published[name]
                update.erases.append(name)
        self.pending = {}
        self.seq_num += 1
        return self._stamped(update)

    def keep_alive(self) -> Any:
        return self._stamped(InteractiveMarkerUpdate(type=InteractiveMarkerUpdate.KEEP_ALIVE))

    def init_message(self) -> Any:
        """update_full's latched message: every marker under the current sequence number."""
        return InteractiveMarkerInit(server_id=self.server_id, seq_num=self.seq_num,
                                     markers=[p.marker for p in self.published.values()])

    def _stamped(self, update: Any) -> Any:
        update.server_id, update.seq_num = self.server_id, self.seq_num
        return update

    def feedback(self, feedback: Any, now: float) -> Callback | None:
        """A client's feedback at `now` (seconds): a POSE_UPDATE moves the marker; the callback
        to call with it (None: none, an unknown marker, or another client's drag in the last second)."""
        published = self.published.get(feedback.marker_name)
        if published is None:
            return None
        if published.last_client_id != feedback.client_id and now - published.last_feedback < CLIENT_CONFLICT_SECONDS:
            return None
        published.last_feedback, published.last_client_id = now, feedback.client_id
        if feedback.event_type == InteractiveMarkerFeedback.POSE_UPDATE:
            stamp = published.marker.header.stamp
            # a marker stamped 0 follows its frame as it moves: it keeps its own header
            keeps_header = stamp.secs == 0 and stamp.nsecs == 0
            header = published.marker.header if keeps_header else feedback.header
            self._move(feedback.marker_name, feedback.pose, header)
        return published.callbacks.for_type(feedback.event_type)
