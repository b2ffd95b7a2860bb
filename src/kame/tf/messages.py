"""geometry_msgs/TransformStamped <-> the buffer core's Transform, duck-typed (any object with
the message's fields works), and times <-> integer nanoseconds."""

from __future__ import annotations

from typing import Any

from .buffer_core import Transform


def to_nsec(stamp: Any) -> int:
    """A Time or Duration (or a float of seconds) in nanoseconds."""
    if isinstance(stamp, (int, float)):
        return round(stamp * 1e9)
    return int(stamp.secs) * 1_000_000_000 + int(stamp.nsecs)


def from_message(msg: Any) -> Transform:
    """Runs for every transform a listener receives: tuple.__new__ skips the named tuple's
    Python-level __new__, and a stamp is read directly when it is a Time."""
    t, r = msg.transform.translation, msg.transform.rotation
    stamp = msg.header.stamp
    nsec = stamp.secs * 1_000_000_000 + stamp.nsecs if hasattr(stamp, "nsecs") else to_nsec(stamp)
    return tuple.__new__(Transform, (msg.header.frame_id, msg.child_frame_id, nsec, (t.x, t.y, t.z),
                                     (r.x, r.y, r.z, r.w)))


def to_message(transform: Transform, message_type: type[Any], time_type: Any) -> Any:
    msg = message_type()
    msg.header.frame_id = transform.parent
    msg.child_frame_id = transform.child
    msg.header.stamp = time_type(transform.stamp // 1_000_000_000, transform.stamp % 1_000_000_000)
    t, r = msg.transform.translation, msg.transform.rotation
    t.x, t.y, t.z = transform.translation
    r.x, r.y, r.z, r.w = transform.rotation
    return msg
