"""roslaunch.parent: ROSLaunchParent (kame.launch.scripting)."""

from kame.launch.scripting import Process, ROSLaunchParent

__all__ = ["Process", "ROSLaunchParent"]
