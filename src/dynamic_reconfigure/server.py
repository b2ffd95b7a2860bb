"""dynamic_reconfigure.server as ROS nodes import it (kame.reconfigure.server)."""

from kame.reconfigure.server import DynamicReconfigureCallbackException, Server

__all__ = ["DynamicReconfigureCallbackException", "Server"]
