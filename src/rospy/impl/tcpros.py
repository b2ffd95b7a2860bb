"""rospy.impl.tcpros: the process's TCPROS handler and server, as rospy's package of its
transport: init_tcpros makes the process's TCPROSServer hand topic connections to the handler's
topic_connection_handler and service connections to tcpros_service's service_connection_handler,
both of which give them to kame's node."""

from __future__ import annotations

from rospy.impl import tcpros_service
from rospy.impl.tcpros_base import DEFAULT_BUFF_SIZE, init_tcpros_server
from rospy.impl.tcpros_pubsub import TCPROSHandler

__all__ = ["DEFAULT_BUFF_SIZE", "TCPROSHandler", "get_tcpros_handler", "init_tcpros", "init_tcpros_server"]

_handler = TCPROSHandler()


def init_tcpros(port: int = 0) -> None:
    """Route the process's TCPROSServer's connections to this node (it serves once started:
    tcpros_base.start_tcpros_server)."""
    server = init_tcpros_server(port)
    server.topic_connection_handler = _handler.topic_connection_handler
    server.service_connection_handler = tcpros_service.service_connection_handler


def get_tcpros_handler() -> TCPROSHandler:
    return _handler
