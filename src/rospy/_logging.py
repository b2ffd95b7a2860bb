"""rospy's log calls (rospy.core's logdebug .. logfatal, their _once, _throttle and
_throttle_identical forms) over kame.client.log, and the once/throttle bookkeeping classes
rospy.core names. The calls take rospy's `logger_name` keyword; kame's lines go to the console,
the node's log file and /rosout as rospy's do."""

from __future__ import annotations

import logging
from typing import Any

from kame.client import log as _log

__all__ = ["LoggingIdentical", "LoggingOnce", "LoggingThrottle", "logdebug", "logdebug_once", "logdebug_throttle",
           "logdebug_throttle_identical", "logerr", "logerr_once", "logerr_throttle", "logerr_throttle_identical",
           "logerror", "logfatal", "logfatal_once", "logfatal_throttle", "logfatal_throttle_identical", "loginfo",
           "loginfo_once", "loginfo_throttle", "loginfo_throttle_identical", "logout", "logwarn", "logwarn_once",
           "logwarn_throttle", "logwarn_throttle_identical", "rospydebug", "rospyerr", "rospyinfo", "rospywarn"]

DEBUG = _log.DEBUG
INFO = _log.INFO
WARN = _log.WARN
ERROR = _log.ERROR
FATAL = _log.FATAL


def logdebug(msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit(DEBUG, msg, args)


def loginfo(msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit(INFO, msg, args)


def logwarn(msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit(WARN, msg, args)


def logerr(msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit(ERROR, msg, args)


def logfatal(msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit(FATAL, msg, args)


logout = loginfo
logerror = logerr


def logdebug_once(msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit_once(DEBUG, msg, args)


def loginfo_once(msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit_once(INFO, msg, args)


def logwarn_once(msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit_once(WARN, msg, args)


def logerr_once(msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit_once(ERROR, msg, args)


def logfatal_once(msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit_once(FATAL, msg, args)


def logdebug_throttle(period: float, msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit_throttle(period, DEBUG, msg, args)


def loginfo_throttle(period: float, msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit_throttle(period, INFO, msg, args)


def logwarn_throttle(period: float, msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit_throttle(period, WARN, msg, args)


def logerr_throttle(period: float, msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit_throttle(period, ERROR, msg, args)


def logfatal_throttle(period: float, msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit_throttle(period, FATAL, msg, args)


def logdebug_throttle_identical(period: float, msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit_throttle_identical(period, DEBUG, msg, args)


def loginfo_throttle_identical(period: float, msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit_throttle_identical(period, INFO, msg, args)


def logwarn_throttle_identical(period: float, msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit_throttle_identical(period, WARN, msg, args)


def logerr_throttle_identical(period: float, msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit_throttle_identical(period, ERROR, msg, args)


def logfatal_throttle_identical(period: float, msg: Any, *args: Any, **kwargs: Any) -> None:
    _log.emit_throttle_identical(period, FATAL, msg, args)


# rospy's own diagnostics: Python logging's `rospy.internal`, never /rosout
_internal = logging.getLogger("rospy.internal")


def rospydebug(msg: Any, *args: Any, **kwargs: Any) -> None:
    _internal.debug(msg, *args, **kwargs)


def rospyinfo(msg: Any, *args: Any, **kwargs: Any) -> None:
    _internal.info(msg, *args, **kwargs)


def rospyerr(msg: Any, *args: Any, **kwargs: Any) -> None:
    _internal.error(msg, *args, **kwargs)


def rospywarn(msg: Any, *args: Any, **kwargs: Any) -> None:
    _internal.warning(msg, *args, **kwargs)


class LoggingThrottle:
    """True for a caller's first call and then once `period` seconds of ROS time have passed
    (again at once if time went backwards)."""

    def __init__(self) -> None:
        self.last_logging_time_table: dict[Any, Any] = {}

    def __call__(self, caller_id: Any, period: float) -> bool:
        from kame.client.clock import Duration, Time

        now = Time.now()
        last = self.last_logging_time_table.get(caller_id)
        if last is None or (now - last) > Duration.from_sec(period):
            self.last_logging_time_table[caller_id] = now
            return True
        if last > now:
            self.last_logging_time_table = {caller_id: now}
            return True
        return False


class LoggingIdentical:
    """True when a caller's message differs from its last one."""

    def __init__(self) -> None:
        self.last_logging_msg_table: dict[Any, str] = {}

    def __call__(self, caller_id: Any, msg: str) -> bool:
        if msg != self.last_logging_msg_table.get(caller_id):
            self.last_logging_msg_table[caller_id] = msg
            return True
        return False


class LoggingOnce:
    """True for a caller's first call only."""

    def __init__(self) -> None:
        self.called_caller_ids: set[Any] = set()

    def __call__(self, caller_id: Any) -> bool:
        if caller_id not in self.called_caller_ids:
            self.called_caller_ids.add(caller_id)
            return True
        return False
