"""rospy.msg: AnyMsg (kame.msg.anymsg), how arguments become a message (kame.client.message_args),
and TCPROS's message frames in a buffer (a 4-byte little-endian length, then the message), as
rospy's transports write and read them."""

from __future__ import annotations

import logging
import struct
from typing import Any

from kame.client.errors import ROSSerializationException
from kame.client.message_args import args_kwds_to_message
from kame.msg.anymsg import AnyMsg
from kame.msg.errors import DeserializationError

__all__ = ["AnyMsg", "args_kwds_to_message", "deserialize_messages", "serialize_message"]

_LENGTH = struct.Struct("<I")


def serialize_message(b: Any, seq: int, msg: Any) -> None:
    """Write `msg` as one frame at `b`'s position (a header's seq set to `seq`, its empty
    frame_id None made "0", as rospy's); ROSSerializationException when a field does not fit."""
    start = b.tell()
    b.seek(start + 4)
    if getattr(msg.__class__, "_has_header", False):
        header = msg.header
        header.seq = seq
        if header.frame_id is None:
            header.frame_id = "0"
    try:
        msg.serialize(b)
    except struct.error as exc:
        raise ROSSerializationException(exc) from exc
    end = b.tell()
    b.seek(start)
    b.write(_LENGTH.pack(end - 4 - start))
    b.seek(end)


def deserialize_messages(b: Any, msg_queue: list[Any], data_class: Any, queue_size: int | None = None,
                         max_msgs: int | None = None, start: int = 0) -> None:
    """Append the whole frames in `b` (from `start` to its position) to `msg_queue` as
    `data_class` messages, at most `max_msgs`, the queue kept to the newest `queue_size`;
    what is left of a partial frame is moved to `start`. DeserializationError on a bad message."""
    try:
        pos = start
        btell = b.tell()
        left = btell - pos
        if left < 4:
            return
        b.seek(pos)
        buffs: list[bytes] = []
        size = -1
        while (size < 0 and left >= 4) or (size > -1 and left >= size):
            if size < 0 and left >= 4:
                (size,) = _LENGTH.unpack(b.read(4))
                left -= 4
            if size > -1 and left >= size:
                buffs.append(b.read(size))
                pos += size + 4
                left = btell - pos
                size = -1
                if max_msgs and len(buffs) >= max_msgs:
                    break
        if queue_size is not None:
            buffs = buffs[-queue_size:]
        for data in buffs:
            msg_queue.append(data_class().deserialize(data))
        if queue_size is not None:
            del msg_queue[:-queue_size]
        if btell == pos:  # every byte read: the buffer starts again at `start`
            b.seek(start)
            b.truncate(start)
        elif pos != start:  # a partial frame is left: moved to `start`
            b.seek(pos)
            leftovers = b.read(btell - pos)
            b.truncate(start + len(leftovers))
            b.seek(start)
            b.write(leftovers)
        else:
            b.seek(btell)
    except Exception as exc:
        logging.getLogger("rospy.msg").error("cannot deserialize message: %s", exc)
        raise DeserializationError(f"cannot deserialize: {exc}") from exc
