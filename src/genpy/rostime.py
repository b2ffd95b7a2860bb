"""genpy.rostime: the ROS time and duration values."""

from kame.rostime import Duration, Time, TVal

__all__ = ["Duration", "TVal", "Time"]
