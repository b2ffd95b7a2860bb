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

import threading
from collections.abc import Callable
from typing import Any

from kame.client import core
from kame.client.errors import ROSInitException, TransportInitError
from kame.msg.message import Message
from kame.protocol import tcpros
from kame.protocol.tcpros import TopicSpec, publisher_reply_fields, subscriber_header_fields
from rospy.core import _ServerProxy, logdebug, logerr, logwarn, rospyerr
from rospy.impl.tcpros_base import (
    DEFAULT_BUFF_SIZE,
    TCPROS,
    TCPROSTransport,
    TCPROSTransportProtocol,
    get_tcpros_server_address,
    start_tcpros_server,
)
from rospy.impl.transport import INBOUND, OUTBOUND

__all__ = ["DEFAULT_BUFF_SIZE", "INBOUND", "OUTBOUND", "TCPROS", "QueuedConnection", "ServerProxy", "TCPROSHandler",
           "TCPROSPub", "TCPROSSub", "TCPROSTransport", "TCPROSTransportProtocol", "check_if_still_publisher",
           "get_tcpros_server_address", "logdebug", "logerr", "logwarn", "robust_connect_subscriber", "rospyerr",
           "start_tcpros_server"]


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

    def shutdown(self) -> None:
        """Nothing to stop: the connections are the node's, which ends them."""

    def create_transport(self, resolved_name: str, pub_uri: str, protocol_params: Any) -> tuple[int, str, int]:
        """Connect this node's subscription of `resolved_name` to the publisher at `pub_uri` too
        (its link negotiates TCPROS with that node itself); (1, ..., port) once it is connecting."""
        if type(protocol_params) is not list or len(protocol_params) != 3:
            return 0, "ERROR: invalid TCPROS parameters", 0
        if protocol_params[0] != TCPROS:
            return 0, f"INTERNAL ERROR: protocol id is not TCPROS: {protocol_params[0]}", 0
        node = core.get_node()
        sub = node.subscriptions.get(resolved_name) if node is not None else None
        if sub is None:
            return 0, f"ERROR: not subscribed to [{resolved_name}]", 0
        sub.add_publisher(pub_uri)
        link = sub.links.get(pub_uri)
        return 1, f"Connected topic[{resolved_name}]. Transport impl[{type(link).__name__}]", protocol_params[2]

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


class QueuedConnection:
    """A connection whose write_data queues (the oldest dropped past `queue_size`, 0: unbounded)
    and returns at once; a thread of its own writes the queue out and ends when the connection
    closes. A write that failed raises at the next write_data. Other attributes are the connection's."""

    def __init__(self, connection: Any, queue_size: int) -> None:
        self._connection = connection
        self._queue_size = queue_size
        self._lock = threading.Lock()
        self._cond_data_available = threading.Condition(self._lock)
        self._connection.set_cleanup_callback(self._closed_connection_callback)
        self._queue: list[bytes] = []
        self._error: BaseException | None = None
        self._thread = threading.Thread(target=self._run, name=f"rospy-queued-{connection.name}", daemon=True)
        self._thread.start()

    def _closed_connection_callback(self, connection: Any) -> None:
        with self._lock:
            self._cond_data_available.notify()

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        return getattr(self._connection, name)

    def write_data(self, data: bytes) -> bool:
        with self._lock:
            if self._error is not None:
                error, self._error = self._error, None
                raise error
            if self._queue_size > 0 and len(self._queue) == self._queue_size:
                del self._queue[0]
            self._queue.append(data)
            self._cond_data_available.notify()
        return True

    def _run(self) -> None:
        while not self._connection.done:
            with self._lock:
                while not self._queue and not self._connection.done:
                    self._cond_data_available.wait()
                queue, self._queue = self._queue, []
            for data in queue:
                try:
                    self._connection.write_data(data)
                except Exception as exc:
                    with self._lock:
                        self._error = exc


ServerProxy = _ServerProxy  # rospy's is xmlrpc.client's; kame's calls go through its own XML-RPC client


def check_if_still_publisher(resolved_topic_name: str, pub_uri: str) -> bool:
    """True when the node at `pub_uri` says it publishes `resolved_topic_name`."""
    try:
        code, _msg, val = ServerProxy(pub_uri).getPublications(core.get_caller_id())
    except Exception:
        return False
    return code == 1 and any(topic == resolved_topic_name for topic, _type in val)


def robust_connect_subscriber(conn: Any, dest_addr: str, dest_port: int, pub_uri: str,
                              receive_cb: Callable[[list[Any], Any], None], resolved_topic_name: str) -> None:
    """Connect `conn` to the publisher, trying again ever more slowly (0.5 s doubling to 30 s)
    while `pub_uri` still publishes the topic, then give its messages to `receive_cb` until it ends."""
    interval = 0.5
    while conn.socket is None and not conn.done and not core.is_shutdown():
        try:
            conn.connect(dest_addr, dest_port, pub_uri, timeout=60.0)
        except TransportInitError as exc:
            if conn.protocol is None:
                conn.done = True
                break
            rospyerr("unable to create subscriber transport: %s.  Will try again in %ss", exc, interval)
            interval = min(interval * 2, 30.0)
            if core.wait_for_shutdown(interval):
                break
            conn.done = not check_if_still_publisher(resolved_topic_name, pub_uri)
    if not conn.done:
        conn.receive_loop(receive_cb)
