"""The one place where the simulator, map_server, map_saver and teleop meet the ROS runtime.

Today that runtime is reached through rospy's public API; when kame's own client runtime
(`kame.client`) lands, only this module changes. Logging follows roscpp's console format, as
the C++ programs these stand in for print it.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import rospy
from rospy import _log

Publisher = rospy.Publisher
Subscriber = rospy.Subscriber
Service = rospy.Service
Time = rospy.Time
get_param = rospy.get_param
has_param = rospy.has_param
is_shutdown = rospy.is_shutdown
on_shutdown = rospy.on_shutdown
signal_shutdown = rospy.signal_shutdown
resolve_name = rospy.resolve_name


def init(name: str, argv: Sequence[str], anonymous: bool = False) -> list[str]:
    """Start the node; returns the arguments left once remappings are taken out."""
    _log.use_roscpp_console()
    rospy.init_node(name, argv=list(argv), anonymous=anonymous)
    return list(rospy.myargv(list(argv)))


def without_remappings(argv: Sequence[str]) -> list[str]:
    return list(rospy.myargv(list(argv)))


def info(msg: str, *args: Any) -> None:
    _log.emit(_log.INFO, msg, args)


def warn(msg: str, *args: Any) -> None:
    _log.emit(_log.WARN, msg, args)


def error(msg: str, *args: Any) -> None:
    _log.emit(_log.ERROR, msg, args)


def warn_throttle(period: float, msg: str, *args: Any) -> None:
    _log.emit_throttle(period, _log.WARN, msg, args)


def wait_for_shutdown(seconds: float | None) -> bool:
    """Wait up to `seconds`; True once the node is shutting down."""
    return bool(rospy.core.wait_for_shutdown(seconds))
