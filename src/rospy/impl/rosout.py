"""rospy.impl.rosout: /rosout from Python's logging. init_rosout starts the node's /rosout
publisher (kame.client.process.start_rosout, which init_node runs unless disable_rosout);
RosOutHandler publishes the records of any logger it is added to on /rosout (not the console),
as the node's own lines are; load_rosout_handlers sets the level from which rospy's log calls
are shown and published.

kame's log calls publish to /rosout themselves (kame.client.log), so load_rosout_handlers adds no
handler to the `rosout` logger, as rospy's does: that would publish each line twice.
"""

from __future__ import annotations

import logging

from kame.client import core, log, process
from kame.client.clock import Time
from kame.client.errors import ROSException
from kame.client.topics import Publisher, Subscriber
from rosgraph_msgs.msg import Log
from rospy.core import _lazy_names, get_caller_id
from rospy.impl.registration import get_topic_manager

__all__ = ["Log", "Publisher", "ROSException", "RosOutHandler", "Subscriber", "Time", "get_caller_id",
           "get_topic_manager", "init_rosout", "load_rosout_handlers"]


def init_rosout() -> bool:
    """Publish the process's log lines on /rosout (from init_node on, if called before it)."""
    core.defer_until_initialized(process.start_rosout)
    return True


class RosOutHandler(logging.Handler):
    """Publishes each record on /rosout at its ROS level, with its file, function and line."""

    def emit(self, record: logging.LogRecord) -> None:
        log.to_rosout(log.level_of(record.levelno), self.format(record), record.filename, record.funcName,
                      record.lineno)


def load_rosout_handlers(level: int | None) -> None:
    """rospy's log calls below `level` (rosgraph_msgs/Log's DEBUG .. FATAL) are dropped; None
    keeps the level."""
    if level is not None:
        log.set_level(level)


__getattr__ = _lazy_names(__name__)
