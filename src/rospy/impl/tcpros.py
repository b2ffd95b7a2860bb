"""rospy.impl.tcpros: the read buffer size, as rospy's package of its transport re-exports it."""

from rospy.impl.tcpros_base import DEFAULT_BUFF_SIZE

__all__ = ["DEFAULT_BUFF_SIZE"]
