"""rospy.impl.init: the node's default ports."""

DEFAULT_NODE_PORT = 0  # bind to any open port
DEFAULT_MASTER_PORT = 11311

__all__ = ["DEFAULT_MASTER_PORT", "DEFAULT_NODE_PORT"]
