"""roslaunch.scriptapi: ROSLaunch (kame.launch.scripting), which launches roslaunch.core.Node."""

from kame.launch.scripting import ROSLaunch
from roslaunch.core import Master, Node, RLException

__all__ = ["Master", "Node", "RLException", "ROSLaunch"]
