"""rospy.rostime: Time, Duration and the ROS clock (kame.client.clock)."""

from kame.client.clock import (
    Duration,
    Time,
    get_rostime,
    get_time,
    is_rostime_initialized,
    is_sim_time,
    set_rostime_initialized,
    set_sim_time,
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
    "switch_to_wallclock",
    "wallsleep",
]


def is_wallclock() -> bool:
    """True unless ROS time comes from /clock (upstream's name for `not is_sim_time()`)."""
    return not is_sim_time()


def switch_to_wallclock() -> None:
    """ROS time follows the wall clock again (after /clock or _set_rostime)."""
    set_sim_time(None)


def _set_rostime(t: Time) -> None:
    """Set simulated ROS time to `t`, waking sleepers (what each /clock message does)."""
    set_sim_time(t)
