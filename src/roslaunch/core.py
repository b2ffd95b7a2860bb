"""roslaunch.core: Node and RLException (kame.launch.scripting)."""

from kame.launch.scripting import Node, RLException

__all__ = ["Node", "RLException"]
