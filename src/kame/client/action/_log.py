"""The action layer's log calls (the caller reported is the action code, as with rospy.logerr)."""

from __future__ import annotations

from typing import Any

from kame.client import log as _log


def logdebug(msg: str, *args: Any) -> None:
    _log.emit(_log.DEBUG, msg, args)


def logwarn(msg: str, *args: Any) -> None:
    _log.emit(_log.WARN, msg, args)


def logerr(msg: str, *args: Any) -> None:
    _log.emit(_log.ERROR, msg, args)
