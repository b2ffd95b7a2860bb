"""dynamic_reconfigure.client as ROS programs import it (kame.reconfigure.client)."""

from kame.reconfigure.client import Client
from kame.reconfigure.errors import DynamicReconfigureCallbackException, DynamicReconfigureParameterException

__all__ = ["Client", "DynamicReconfigureCallbackException", "DynamicReconfigureParameterException"]
