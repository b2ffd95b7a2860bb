"""rospy.timer: Rate, Timer and sleep on ROS time (kame.client.timer)."""

from kame.client.timer import (
    Rate,
    Timer,
    TimerEvent,
    sleep,
)

__all__ = [
    "Rate",
    "Timer",
    "TimerEvent",
    "sleep",
]
