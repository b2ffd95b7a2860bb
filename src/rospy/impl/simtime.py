"""rospy.impl.simtime: simulated time. init_simtime follows /clock when /use_sim_time is true
(kame.client.process.start_time, which init_node runs unless disable_rostime); the names of the
topic and parameter, and whether the parameter is on."""

from __future__ import annotations

from kame.client import core, process
from rosgraph_msgs.msg import Clock

__all__ = ["Clock", "init_simtime"]

_ROSCLOCK = "/clock"
_USE_SIMTIME = "/use_sim_time"


def _is_use_simtime() -> bool:
    """True when the parameter server's /use_sim_time is true."""
    return bool(process.get_param(_USE_SIMTIME, False))


def init_simtime() -> bool:
    """Initialize ROS time, following /clock when /use_sim_time is true (from init_node on, if
    called before it)."""
    core.defer_until_initialized(process.start_time)
    return True

