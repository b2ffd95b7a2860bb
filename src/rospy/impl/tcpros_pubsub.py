"""rospy.impl.tcpros_pubsub: the TCPROS side of topics as rospy names it. TCPROSSub and
TCPROSPub are the connection headers a subscriber sends and a publisher answers with (kame's
TCPROS codec writes them: kame.protocol.tcpros); TCPROSHandler is the protocol's entry in
requestTopic, answering with this process's node's TCPROS server.

The connections themselves (rospy's TCPROSTransport, create_transport, QueuedConnection) are
kame's node's (kame.node.topics), which keeps no such objects to hand out.
"""

from __future__ import annotations

from typing import Any

from kame.client import core
from kame.client.errors import ROSInitException, TransportInitError
from kame.msg.message import Message
from kame.protocol.tcpros import TopicSpec, publisher_reply_fields, subscriber_header_fields
from rospy.impl.tcpros_base import DEFAULT_BUFF_SIZE, TCPROS
from rospy.impl.transport import INBOUND, OUTBOUND

__all__ = ["TCPROSHandler", "TCPROSPub", "TCPROSSub"]


def _message_class(data_class: Any) -> Any:
    if data_class is not None and not (isinstance(data_class, type) and issubclass(data_class, Message)):
        raise TransportInitError("Unable to initialize transport: data class is not a message data class")
    return data_class


class TCPROSSub:
    """A subscription's side of a connection to a publisher of `resolved_name`."""

    def __init__(self, resolved_name: str, recv_data_class: Any, queue_size: int | None = None,
                 buff_size: int = DEFAULT_BUFF_SIZE, tcp_nodelay: bool = False) -> None:
        self.resolved_name = resolved_name
        self.recv_data_class = _message_class(recv_data_class)
        self.queue_size = queue_size
        self.buff_size = buff_size
        self.tcp_nodelay = tcp_nodelay
        self.direction = INBOUND

    def get_header_fields(self) -> dict[str, str]:
        """The connection header the subscriber sends."""
        cls = self.recv_data_class
        return subscriber_header_fields(callerid=core.get_caller_id(), topic=self.resolved_name, type=cls._type,
                                        md5sum=cls._md5sum, message_definition=cls._full_text,
                                        tcp_nodelay=self.tcp_nodelay)


class TCPROSPub:
    """A publication's side of a connection: the header it answers a subscriber with
    (`headers` added, overriding, as rospy's Publisher(headers=...))."""

    def __init__(self, resolved_name: str, pub_data_class: Any, is_latch: bool = False,
                 headers: dict[str, str] | None = None) -> None:
        self.resolved_name = resolved_name
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
