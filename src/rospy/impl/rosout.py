"""rospy.impl.rosout: /rosout from Python's logging. RosOutHandler publishes the records of any
logger it is added to on /rosout (not the console), as the node's own lines are; load_rosout_handlers
sets the level from which rospy's log calls are shown and published.

kame's log calls publish to /rosout themselves (kame.client.log), so load_rosout_handlers adds no
handler to the `rosout` logger, as rospy's does: that would publish each line twice.
"""

from __future__ import annotations

import logging

from kame.client import log

__all__ = ["RosOutHandler", "load_rosout_handlers"]


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
