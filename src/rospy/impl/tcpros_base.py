"""rospy.impl.tcpros_base: TCPROS connections as rospy's objects, over kame's sockets.

- TCPServer accepts on kame.net.stream's Listener; TCPROSServer reads each connection's header
  (kame.net.handshake) on a worker it owns and hands the socket to its topic or service
  connection handler (rospy.impl.tcpros sets them to ones that give it to kame's node).
- TCPROSTransport is a real TCPROS connection: connect() dials a publisher or service with its
  protocol's header and checks the answer; send_message, write_data, receive_once and
  receive_loop move frames (rospy.msg's framing). It does not reconnect: receive_loop ends when
  the peer goes (kame's own subscriptions reconnect, kame.node.publisher_link).
- recv_buff reads what a socket has into a buffer, as rospy's transports do.
"""

from __future__ import annotations

import errno
import logging
import os
import threading
from collections.abc import Callable
from errno import EAGAIN, EWOULDBLOCK
from io import BytesIO, StringIO
from typing import Any

from kame.client import core as _client_core
from kame.client.errors import (
    ROSInitException,
    ROSInternalException,
    TransportException,
    TransportInitError,
    TransportTerminated,
)
from kame.client.services import ServiceException
from kame.msg.errors import DeserializationError
from kame.msg.message import Message
from kame.net import handshake, stream
from kame.net.workers import WorkerPool
from kame.protocol.tcpros import encode_header, error_header_fields
from rospy.core import *  # noqa: F403  (rospy.impl.tcpros_base re-exports rospy.core, as rospy's)
from rospy.core import __all__ as _core_names
from rospy.core import _lazy_names, is_shutdown, is_shutdown_requested, logdebug, logwarn
from rospy.impl.transport import BIDIRECTIONAL, Transport
from rospy.msg import deserialize_messages, serialize_message

__all__ = [*_core_names, "BIDIRECTIONAL", "DEFAULT_BUFF_SIZE", "EAGAIN", "EWOULDBLOCK", "TCPROS", "BytesIO",
           "DeserializationError", "Message", "ROSInitException", "ROSInternalException", "ServiceException",
           "StringIO", "TCPROSServer", "TCPROSTransport", "TCPROSTransportProtocol", "TCPServer", "Transport",
           "TransportException", "TransportInitError", "TransportTerminated", "deserialize_messages",
           "get_tcpros_server_address", "init_tcpros_server", "logger", "python3", "read_ros_handshake_header",
           "recv_buff", "serialize_message", "start_tcpros_server", "write_ros_handshake_header"]

python3 = 1
logger = logging.getLogger("rospy.tcpros")

DEFAULT_BUFF_SIZE = 65536  # rospy's recv size; Subscriber's buff_size defaults to it
TCPROS = "TCPROS"  # the protocol name in requestTopic and getBusInfo
HEADER_TIMEOUT = 10.0  # a peer gets this long to send its whole connection header (kame's node's rule)


def recv_buff(sock: Any, b: Any, buff_size: int) -> int:
    """Read what `sock` has (up to `buff_size` bytes) into `b`; the count, 0 if a non-blocking
    socket had nothing; TransportTerminated when the peer closed or the read failed."""
    try:
        data = stream.receive(sock, buff_size)
    except OSError as exc:
        if exc.errno in (EAGAIN, EWOULDBLOCK):
            return 0
        raise TransportTerminated("unable to receive data from sender, check sender's logs for details") from exc
    if not data:
        raise TransportTerminated("unable to receive data from sender, check sender's logs for details")
    b.write(data)
    return len(data)


def read_ros_handshake_header(sock: Any, b: Any, buff_size: int) -> dict[str, str]:
    """The connection header `sock` sends (whole within HEADER_TIMEOUT); TransportInitError if
    it is malformed or does not come."""
    try:
        header = handshake.read_header(sock, HEADER_TIMEOUT)
    except (OSError, handshake.HandshakeError) as exc:
        raise TransportInitError(f"Remote end failed to send a connection header: {exc}") from exc
    sock.settimeout(None)
    return header


def write_ros_handshake_header(sock: Any, header: dict[str, str]) -> int:
    """Send the connection header `header`; the bytes sent."""
    data = encode_header(header)
    handshake.write_header(sock, header)
    return len(data)


class TCPServer:
    """Accepts TCP connections on `port` (0: any free one) of the bind address and gives each
    socket to `inbound_handler(sock, (host, port))`, from construction until shutdown()."""

    def __init__(self, inbound_handler: Callable[[Any, Any], None], port: int = 0) -> None:
        from rosgraph import network

        self.inbound_handler = inbound_handler
        self.is_shutdown = False
        self._stopped = threading.Event()
        self._listener = stream.Listener(network.get_bind_address(), port, self._accept, name="rospy-tcpserver")
        self.addr = self._listener.sock.getsockname()[0]
        self.port = self._listener.port

    def _accept(self, sock: Any, addr: Any) -> None:
        if self.is_shutdown:
            sock.close()
            return
        self.inbound_handler(sock, addr)

    def start(self) -> None:
        """Nothing left to start: the server accepts from construction (its thread is kame's Listener's)."""

    def run(self) -> None:
        """Block until shutdown()."""
        self._stopped.wait()

    def get_full_addr(self) -> tuple[str, int]:
        from rosgraph import network

        return network.get_host_name(), self.port

    def shutdown(self) -> None:
        if not self.is_shutdown:
            self.is_shutdown = True
            self._listener.close()
            self._stopped.set()


def _error_connection_handler(sock: Any, client_addr: Any, header: dict[str, str]) -> str | None:
    return "unhandled connection"


class TCPROSServer:
    """A TCPROS server: reads each connection's header and gives the socket to
    topic_connection_handler or service_connection_handler (an error text refuses it)."""

    def __init__(self, port: int = 0) -> None:
        self.port = port
        self.tcp_ros_server: TCPServer | None = None
        self.lock = threading.Lock()
        self.topic_connection_handler: Callable[[Any, Any, dict[str, str]], str | None] = _error_connection_handler
        self.service_connection_handler: Callable[[Any, Any, dict[str, str]], str | None] = _error_connection_handler
        self._workers: WorkerPool | None = None

    def start_server(self) -> tuple[int, str, list[Any]] | None:
        with self.lock:
            if self.tcp_ros_server is not None:
                return None
            try:
                self._workers = WorkerPool("rospy-tcpros")
                self.tcp_ros_server = TCPServer(self._tcp_server_callback, self.port)
            except OSError as exc:
                self.tcp_ros_server = None
                logger.error("unable to start TCPROS server: %s", exc)
                return 0, f"unable to establish TCPROS server: {exc}", []
        return None

    def get_address(self) -> tuple[str | None, int | None]:
        if self.tcp_ros_server is not None:
            return self.tcp_ros_server.get_full_addr()
        return None, None

    def shutdown(self, reason: str = "") -> None:
        with self.lock:
            server, workers = self.tcp_ros_server, self._workers
        if server is not None:
            server.shutdown()
        if workers is not None:
            workers.close(timeout=2.0)

    def _tcp_server_callback(self, sock: Any, client_addr: Any) -> None:
        workers = self._workers
        if workers is None:
            sock.close()
            return
        workers.submit(lambda: self._serve(sock, client_addr))

    def _serve(self, sock: Any, client_addr: Any) -> None:
        try:
            header = read_ros_handshake_header(sock, BytesIO(), 4096)
            if "topic" in header:
                err_msg = self.topic_connection_handler(sock, client_addr, header)
            elif "service" in header:
                err_msg = self.service_connection_handler(sock, client_addr, header)
            else:
                err_msg = "no topic or service name detected"
            if err_msg:
                text = "node shutting down" if is_shutdown_requested() else err_msg
                write_ros_handshake_header(sock, error_header_fields(text))
                if not is_shutdown_requested():
                    logwarn(f"Could not process inbound connection: {err_msg}{header}")
                sock.close()
        except Exception as exc:
            if not is_shutdown_requested():
                logwarn("Inbound TCP/IP connection failed: %s", exc)
            sock.close()


_tcpros_server: TCPROSServer | None = None


def init_tcpros_server(port: int = 0) -> TCPROSServer:
    """The process's TCPROSServer (made once; shut down with the node)."""
    global _tcpros_server
    if _tcpros_server is None:
        _tcpros_server = TCPROSServer(port=port)
        _client_core.add_shutdown_hook(_tcpros_server.shutdown)
    return _tcpros_server


def start_tcpros_server() -> tuple[int, str, list[Any]] | None:
    return init_tcpros_server().start_server()


def get_tcpros_server_address() -> tuple[str | None, int | None]:
    """Where this process serves TCPROS: the started TCPROSServer's address, else kame's node's."""
    if _tcpros_server is not None and _tcpros_server.tcp_ros_server is not None:
        return _tcpros_server.get_address()
    node = _client_core.get_node()
    if node is not None:
        return node.config.host, node.tcpros_port
    return None, None


class TCPROSTransportProtocol:
    """What a transport's connection header says and how its frames are read."""

    def __init__(self, resolved_name: str, recv_data_class: Any, queue_size: int | None = None,
                 buff_size: int = DEFAULT_BUFF_SIZE) -> None:
        if recv_data_class and not issubclass(recv_data_class, Message):
            raise TransportInitError("Unable to initialize transport: data class is not a message data class")
        self.resolved_name = resolved_name
        self.recv_data_class = recv_data_class
        self.queue_size = queue_size
        self.buff_size = buff_size
        self.direction = BIDIRECTIONAL

    def read_messages(self, b: Any, msg_queue: list[Any], sock: Any) -> None:
        deserialize_messages(b, msg_queue, self.recv_data_class, queue_size=self.queue_size)

    def get_header_fields(self) -> dict[str, str]:
        return {}


class TCPROSTransport(Transport):
    """A TCPROS connection for `protocol` (TCPROSSub, TCPROSPub, TCPService, TCPROSServiceClient)."""

    transport_type = "TCPROS"

    def __init__(self, protocol: Any, name: str, header: dict[str, str] | None = None) -> None:
        super().__init__(protocol.direction, name=name)
        if not name:
            raise TransportInitError("Unable to initialize transport: name is not set")
        self.protocol = protocol
        self.socket: Any = None
        self.endpoint_id = "unknown"
        self.callerid_pub = "unknown"
        self.dest_address: tuple[str, int] | None = None
        self.read_buff: Any = BytesIO()
        self.write_buff: Any = BytesIO()
        self.header = header
        self.is_latched = False
        self.latch: Any = None
        self._fileno: int | None = None
        self.md5sum: str | None = None
        self.type: str | None = None
        self.local_endpoint = (None, None)
        self.remote_endpoint = (None, None)

    def get_transport_info(self) -> str:
        return (f"{self.transport_type} connection on port {self.local_endpoint[1]} to "
                f"[{self.remote_endpoint[0]}:{self.remote_endpoint[1]} on socket {self._fileno}]")

    def fileno(self) -> int | None:
        return self._fileno

    def set_endpoint_id(self, endpoint_id: str) -> None:
        self.endpoint_id = endpoint_id

    def set_socket(self, sock: Any, endpoint_id: str) -> None:
        if self.socket is not None:
            raise TransportInitError("socket already initialized")
        self.socket = sock
        self.endpoint_id = endpoint_id
        self._fileno = sock.fileno()
        self.local_endpoint = sock.getsockname()

    def connect(self, dest_addr: str, dest_port: int, endpoint_id: str, timeout: float | None = None) -> None:
        """Dial `dest_addr:dest_port`, send the protocol's header and check the answer;
        TransportInitError when either fails."""
        if os.environ.get("ROS_HOSTNAME") == "localhost":
            from rosgraph import network

            if not network.is_local_address(dest_addr):
                self.close()
                raise TransportInitError(f"attempted to connect to non-local host [{dest_addr}] from a node "
                                         "launched with ROS_HOSTNAME=localhost")
        self.endpoint_id = endpoint_id
        self.dest_address = (dest_addr, dest_port)
        try:
            self.socket = stream.connect(dest_addr, dest_port, timeout if timeout is not None else HEADER_TIMEOUT)
            if timeout is None:
                self.socket.settimeout(None)
            self._fileno = self.socket.fileno()
            self.write_header()
            self.read_header()
            self.local_endpoint = self.socket.getsockname()
            self.remote_endpoint = (dest_addr, dest_port)
        except TransportInitError:
            raise
        except OSError as exc:
            if exc.errno not in (errno.ENETDOWN, errno.ENETUNREACH, errno.ENETRESET, errno.ECONNABORTED,
                                 errno.ETIMEDOUT, errno.EHOSTDOWN, errno.EHOSTUNREACH):
                self.close()
            raise TransportInitError(str(exc)) from exc

    def _validate_header(self, header: dict[str, str]) -> None:
        self.header = header
        if "error" in header:
            raise TransportInitError(f"remote error reported: {header['error']}")
        for required in ("md5sum", "type"):
            if required not in header:
                raise TransportInitError(f"header missing required field [{required}]")
        self.type = header["type"]
        self.md5sum = header["md5sum"]
        self.callerid_pub = header.get("callerid", self.callerid_pub)
        if header.get("latching", "0") == "1":
            self.is_latched = True

    def write_header(self) -> None:
        if self.socket is None or self.protocol is None:
            return
        self.stat_bytes += write_ros_handshake_header(self.socket, self.protocol.get_header_fields())

    def read_header(self) -> None:
        if self.socket is None:
            return
        self._validate_header(read_ros_handshake_header(self.socket, self.read_buff, self.protocol.buff_size))

    def send_message(self, msg: Any, seq: int) -> None:
        serialize_message(self.write_buff, seq, msg)
        self.write_data(self.write_buff.getvalue())
        self.write_buff.truncate(0)
        self.write_buff.seek(0)

    def write_data(self, data: bytes) -> bool:
        if not self.socket:
            raise TransportInitError("TCPROS transport was not successfully initialized")
        if self.done:
            raise TransportTerminated("connection closed")
        try:
            self.socket.sendall(data)
        except OSError as exc:
            self.close()
            raise TransportTerminated(str(exc)) from exc
        self.stat_bytes += len(data)
        self.stat_num_msg += 1
        return True

    def receive_once(self) -> list[Any]:
        """The next message(s) from the peer, each given this connection's header."""
        sock = self.socket
        if sock is None:
            raise TransportException("connection not initialized")
        b = self.read_buff
        msg_queue: list[Any] = []
        protocol = self.protocol
        try:
            while not msg_queue and not self.done and not is_shutdown():
                if b.tell() >= 4:
                    protocol.read_messages(b, msg_queue, sock)
                if not msg_queue:
                    self.stat_bytes += recv_buff(sock, b, protocol.buff_size)
        except DeserializationError as exc:
            raise TransportException(f"receive_once[{self.name}]: DeserializationError {exc}") from exc
        except (TransportTerminated, ServiceException):
            raise
        except Exception as exc:
            raise TransportException(f"receive_once[{self.name}]: unexpected error {exc}") from exc
        self.stat_num_msg += len(msg_queue)
        for msg in msg_queue:
            msg._connection_header = self.header
        if self.is_latched and msg_queue:
            self.latch = msg_queue[-1]
        return msg_queue

    def receive_loop(self, msgs_callback: Callable[[list[Any], TCPROSTransport], None]) -> None:
        """Give each batch of messages to `msgs_callback(msgs, self)` until the connection or the node ends."""
        try:
            while not self.done and not is_shutdown() and self.socket is not None:
                try:
                    msgs = self.receive_once()
                except TransportException as exc:
                    logdebug("[%s] failed to receive incoming message : %s", self.name, exc)
                    break
                if not self.done and not is_shutdown():
                    msgs_callback(msgs, self)
        finally:
            if not self.done:
                self.close()

    def close(self) -> None:
        if self.done:
            return
        if self.socket is not None:
            stream.shut_down(self.socket)
            self.socket.close()
        self.socket = self.read_buff = self.write_buff = self.protocol = None
        super().close()

__getattr__ = _lazy_names(__name__)
