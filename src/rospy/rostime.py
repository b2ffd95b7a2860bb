"""rospy.rostime: Time, Duration and the ROS clock (kame.client.clock)."""

from threading import Condition

from kame.client.clock import (
    Duration,
    Time,
    get_rostime,
    get_time,
    is_rostime_initialized,
    is_sim_time,
    rostime_changed,
    set_rostime_initialized,
    set_sim_time,
    wallsleep,
)

__all__ = [
    "Duration",
    "Time",
    "get_rostime",
    "get_rostime_cond",
    "get_time",
    "is_rostime_initialized",
    "is_sim_time",
    "is_wallclock",
    "set_rostime_initialized",
    "switch_to_wallclock",
    "wallsleep",
]


def get_rostime_cond() -> Condition:
    """The condition notified at each change of ROS time (a /clock message, the switch to the wall clock)."""
    return rostime_changed


def is_wallclock() -> bool:
    """True unless ROS time comes from /clock (upstream's name for `not is_sim_time()`)."""
    return not is_sim_time()


def switch_to_wallclock() -> None:
    """ROS time follows the wall clock again (after /clock or _set_rostime)."""
    set_sim_time(None)


def _set_rostime(t: Time) -> None:
    """Set simulated ROS time to `t`, waking sleepers (what each /clock message does)."""
    set_sim_time(t)
