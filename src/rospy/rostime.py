"""rospy.rostime: Time, Duration and the ROS clock (kame.client.clock)."""

from kame.client.clock import (
    Duration,
    Time,
    get_rostime,
    get_time,
    is_rostime_initialized,
    is_sim_time,
    set_rostime_initialized,
    wallsleep,
)

__all__ = [
    "Duration",
    "Time",
    "get_rostime",
    "get_time",
    "is_rostime_initialized",
    "is_sim_time",
    "is_wallclock",
    "set_rostime_initialized",
    "wallsleep",
]


def is_wallclock() -> bool:
    """True unless ROS time comes from /clock (upstream's name for `not is_sim_time()`)."""
    return not is_sim_time()
