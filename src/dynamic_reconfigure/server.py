"""dynamic_reconfigure.server as ROS nodes import it (kame.reconfigure.server)."""

from kame.reconfigure.errors import DynamicReconfigureCallbackException
from kame.reconfigure.server import Server

__all__ = ["DynamicReconfigureCallbackException", "Server"]
