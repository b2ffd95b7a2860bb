"""rospy.impl.transport: the directions of a connection, as getBusInfo reports them."""

INBOUND = "i"
OUTBOUND = "o"
BIDIRECTIONAL = "b"

__all__ = ["BIDIRECTIONAL", "INBOUND", "OUTBOUND"]
