"""rospy.impl.tcpros_base: the TCPROS protocol name and the read buffer size programs size theirs by."""

DEFAULT_BUFF_SIZE = 65536  # rospy's recv size; Subscriber's buff_size defaults to it
TCPROS = "TCPROS"  # the protocol name in requestTopic and getBusInfo

__all__ = ["DEFAULT_BUFF_SIZE", "TCPROS"]
