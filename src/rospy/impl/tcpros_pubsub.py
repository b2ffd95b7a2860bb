"""rospy.impl.tcpros_pubsub: the TCPROS side of topics as rospy names it. TCPROSSub and
TCPROSPub are the connection headers a subscriber sends and a publisher answers with (kame's
TCPROS codec writes them: kame.protocol.tcpros); TCPROSHandler is the protocol's entry in
requestTopic, answering with this process's node's TCPROS server.

topic_connection_handler gives a subscriber's connection (its header read by a TCPROSServer)
to this node's publication, which serves it as any other (kame.node.topics). TCPROSTransport,
with TCPROSSub as its protocol, subscribes on a connection of its own
(rospy.impl.tcpros_base); kame's Subscriber makes and keeps its connections itself.
"""

from __future__ import annotations

from typing import Any

from kame.client import core
from kame.client.errors import ROSInitException, TransportInitError
from kame.msg.message import Message
from kame.protocol import tcpros
from kame.protocol.tcpros import TopicSpec, publisher_reply_fields, subscriber_header_fields
from rospy.core import logdebug, logerr, logwarn, rospyerr
from rospy.impl.tcpros_base import (
    DEFAULT_BUFF_SIZE,
    TCPROS,
    TCPROSTransport,
    TCPROSTransportProtocol,
    get_tcpros_server_address,
    start_tcpros_server,
)
from rospy.impl.transport import INBOUND, OUTBOUND

__all__ = ["DEFAULT_BUFF_SIZE", "INBOUND", "OUTBOUND", "TCPROS", "TCPROSHandler", "TCPROSPub", "TCPROSSub",
           "TCPROSTransport", "TCPROSTransportProtocol", "get_tcpros_server_address", "logdebug", "logerr", "logwarn",
           "rospyerr", "start_tcpros_server"]


def _message_class(data_class: Any) -> Any:
    if data_class is not None and not (isinstance(data_class, type) and issubclass(data_class, Message)):
        raise TransportInitError("Unable to initialize transport: data class is not a message data class")
    return data_class


class TCPROSSub(TCPROSTransportProtocol):
    """A subscription's side of a connection to a publisher of `resolved_name`."""

    def __init__(self, resolved_name: str, recv_data_class: Any, queue_size: int | None = None,
                 buff_size: int = DEFAULT_BUFF_SIZE, tcp_nodelay: bool = False) -> None:
        super().__init__(resolved_name, _message_class(recv_data_class), queue_size, buff_size)
        self.tcp_nodelay = tcp_nodelay
        self.direction = INBOUND

    def get_header_fields(self) -> dict[str, str]:
        """The connection header the subscriber sends."""
        cls = self.recv_data_class
        return subscriber_header_fields(callerid=core.get_caller_id(), topic=self.resolved_name, type=cls._type,
                                        md5sum=cls._md5sum, message_definition=cls._full_text,
                                        tcp_nodelay=self.tcp_nodelay)


class TCPROSPub(TCPROSTransportProtocol):
    """A publication's side of a connection: the header it answers a subscriber with
    (`headers` added, overriding, as rospy's Publisher(headers=...))."""

    def __init__(self, resolved_name: str, pub_data_class: Any, is_latch: bool = False,
                 headers: dict[str, str] | None = None) -> None:
        super().__init__(resolved_name, None)
        self.pub_data_class = _message_class(pub_data_class)
        self.is_latch = is_latch
        self.headers = headers or {}
        self.direction = OUTBOUND

    def get_header_fields(self) -> dict[str, str]:
        cls = self.pub_data_class
        spec = TopicSpec(cls._type, cls._md5sum, cls._full_text, self.is_latch)
        return publisher_reply_fields(callerid=core.get_caller_id(), topic=self.resolved_name, spec=spec,
                                      extra=self.headers)


class TCPROSHandler:
    """TCPROS in protocol negotiation (requestTopic): which protocols, and where to connect."""

    def __init__(self) -> None:
        self.tcp_nodelay_map: dict[str, bool] = {}

    def set_tcp_nodelay(self, resolved_name: str, tcp_nodelay: bool) -> None:
        self.tcp_nodelay_map[resolved_name] = tcp_nodelay

    def supports(self, protocol: str) -> bool:
        return protocol == TCPROS

    def get_supported(self) -> list[list[str]]:
        return [[TCPROS]]

    def init_publisher(self, resolved_name: str, protocol: list[Any]) -> tuple[int, str, list[Any]]:
        """(1, 'ready on host:port', [TCPROS, host, port]): this node's TCPROS server."""
        if protocol[0] != TCPROS:
            return 0, f"Internal error: protocol does not match TCPROS: {protocol}", []
        node = core.get_node()
        if node is None:
            raise ROSInitException("TCPROS is served by the node: call init_node() first")
        return 1, f"ready on {node.config.host}:{node.tcpros_port}", [TCPROS, node.config.host, node.tcpros_port]

    def topic_connection_handler(self, sock: Any, client_addr: Any, header: dict[str, str]) -> str | None:
        """Give a subscriber's connection, whose header `header` was read, to this node's
        publication of its topic; the reason it is refused, or None once the publication has it."""
        node = core.get_node()
        if node is None:
            refused = tcpros.accept_subscriber(header, callerid=core.get_caller_id(), publications={})
            return refused.error if isinstance(refused, tcpros.Rejected) else "node not initialized"
        return node.connect_subscriber(sock, header)
