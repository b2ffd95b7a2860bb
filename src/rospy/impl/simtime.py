"""rospy.impl.simtime: simulated time. kame's init_node follows /clock when /use_sim_time is
true (kame.client.process), so nothing here starts it; the names of the topic and parameter,
and whether the parameter is on."""

from __future__ import annotations

from kame.client import process

__all__: list[str] = []

_ROSCLOCK = "/clock"
_USE_SIMTIME = "/use_sim_time"


def _is_use_simtime() -> bool:
    """True when the parameter server's /use_sim_time is true."""
    return bool(process.get_param(_USE_SIMTIME, False))
