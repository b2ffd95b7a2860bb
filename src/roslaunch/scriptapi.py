"""roslaunch.scriptapi: ROSLaunch (kame.launch.scripting)."""

from kame.launch.scripting import ROSLaunch

__all__ = ["ROSLaunch"]
