"""The one place where the simulator, map_server, map_saver and teleop meet the ROS runtime.

The runtime is kame's own (`kame.client`, what rospy re-exports). Logging follows roscpp's
console format, as the C++ programs these stand in for print it.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from kame.client import clock, core, process, services, topics
from kame.client import log as _log

Publisher = topics.Publisher
Subscriber = topics.Subscriber
Service = services.Service
Time = clock.Time
get_param = process.get_param
has_param = process.has_param
is_shutdown = core.is_shutdown
on_shutdown = core.on_shutdown
signal_shutdown = core.signal_shutdown
resolve_name = core.resolve_name


def init(name: str, argv: Sequence[str], anonymous: bool = False) -> list[str]:
    """Start the node; returns the arguments left once remappings are taken out."""
    _log.use_roscpp_console()
    process.init_node(name, argv=list(argv), anonymous=anonymous)
    return list(process.myargv(list(argv)))


def without_remappings(argv: Sequence[str]) -> list[str]:
    return list(process.myargv(list(argv)))


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
    return bool(core.wait_for_shutdown(seconds))
