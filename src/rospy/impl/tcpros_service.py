"""rospy.impl.tcpros_service: where rospy's Service, ServiceProxy and wait_for_service live
(programs import them from here too: kame.client.services), and the TCPROS side of services:
TCPService and TCPROSServiceClient (a server's and a client's connection header and how a
response is read, for a TCPROSTransport), convert_return_to_response, and
service_connection_handler, which gives a client's connection to kame's node's service."""

from __future__ import annotations

import logging
import struct
from typing import Any

from kame.client import core as _client_core
from kame.client.errors import ROSException, ROSInterruptException, TransportInitError, TransportTerminated
from kame.client.services import Service, ServiceException, ServiceImpl, ServiceProxy, wait_for_service
from kame.msg.message import Message
from kame.protocol import tcpros
from rospy.core import isstring, logdebug, logerr, loginfo, logwarn
from rospy.impl.registration import get_service_manager
from rospy.impl.tcpros_base import (
    DEFAULT_BUFF_SIZE,
    TCPROSTransport,
    TCPROSTransportProtocol,
    get_tcpros_server_address,
    recv_buff,
    start_tcpros_server,
)
from rospy.msg import deserialize_messages

__all__ = ["DEFAULT_BUFF_SIZE", "ROSException", "ROSInterruptException", "Service", "ServiceException",
           "ServiceImpl", "ServiceProxy", "TCPROSServiceClient", "TCPROSTransport", "TCPROSTransportProtocol",
           "TCPService", "TransportInitError", "TransportTerminated", "convert_return_to_response",
           "get_service_manager", "get_tcpros_server_address", "isstring", "logdebug", "logerr", "logger", "loginfo",
           "logwarn", "recv_buff", "service_connection_handler", "start_tcpros_server", "wait_for_service"]

logger = logging.getLogger("rospy.service")


def convert_return_to_response(response: Any, response_class: Any) -> Any:
    """A service handler's return value as a `response_class` message: the message itself, a
    dict of fields, one value or a tuple of them; ServiceException for None or a mismatch."""
    if isinstance(response, Message) and response._type == response_class._type:
        return response
    if type(response) is dict:
        try:
            return response_class(**response)
        except AttributeError as exc:
            raise ServiceException(f"handler returned invalid value: {exc}") from exc
    if response is None:
        raise ServiceException("service handler returned None")
    if type(response) not in (list, tuple):
        try:
            return response_class(response)
        except TypeError as exc:
            raise ServiceException(f"handler returned invalid value: {exc}") from exc
    try:
        return response_class(*response)
    except TypeError as exc:
        raise ServiceException(f"handler returned wrong number of values: {exc}") from exc


def service_connection_handler(sock: Any, client_addr: Any, header: dict[str, str]) -> str | None:
    """Give a service client's connection, whose header `header` was read, to this node's
    service (served on a thread the node owns); the reason it is refused, or None."""
    node = _client_core.get_node()
    specs = {name: server.spec for name, server in dict(node.services).items()} if node is not None else {}
    checked = tcpros.accept_service_client(header, callerid=_client_core.get_caller_id(), services=specs)
    if isinstance(checked, tcpros.Rejected):
        return checked.error
    assert node is not None  # accepted: the node serves the service
    logger.debug("connection from %s:%s", client_addr[0], client_addr[1])

    def serve() -> None:
        refused = node.connect_service_client(sock, header)
        if refused is not None:  # the service went between the check and now
            sock.close()

    node.spawn(serve, f"rospy-service-{checked.service}")
    return None


class TCPService(TCPROSTransportProtocol):
    """A service server's side of a connection: the header it answers with."""

    def __init__(self, resolved_name: str, service_class: Any, buff_size: int = DEFAULT_BUFF_SIZE) -> None:
        super().__init__(resolved_name, service_class._request_class, buff_size=buff_size)
        self.service_class = service_class

    def get_header_fields(self) -> dict[str, str]:
        return {"service": self.resolved_name, "type": self.service_class._type,
                "md5sum": self.service_class._md5sum, "callerid": _client_core.get_caller_id()}


class TCPROSServiceClient(TCPROSTransportProtocol):
    """A service client's side of a connection: its header, and a response read past its ok
    byte (ServiceException carrying the server's error text when it is 0)."""

    def __init__(self, resolved_name: str, service_class: Any, headers: dict[str, str] | None = None,
                 buff_size: int = DEFAULT_BUFF_SIZE) -> None:
        super().__init__(resolved_name, service_class._response_class)
        self.service_class = service_class
        self.headers = headers or {}
        self.buff_size = buff_size

    def get_header_fields(self) -> dict[str, str]:
        return {"service": self.resolved_name, "md5sum": self.service_class._md5sum,
                "callerid": _client_core.get_caller_id(), **self.headers}

    def _read_ok_byte(self, b: Any, sock: Any) -> None:
        if b.tell() == 0:
            return
        pos = b.tell()
        b.seek(0)
        ok = b.read(1)[0]
        b.seek(pos)
        if not ok:
            text = self._read_service_error(sock, b)
            b.seek(0)
            b.truncate(0)
            raise ServiceException(f"service [{self.resolved_name}] responded with an error: {text!r}")

    def read_messages(self, b: Any, msg_queue: list[Any], sock: Any) -> None:
        self._read_ok_byte(b, sock)
        deserialize_messages(b, msg_queue, self.recv_data_class, queue_size=self.queue_size, max_msgs=1, start=1)
        if b.tell() == 1:
            b.seek(0)

    def _read_service_error(self, sock: Any, b: Any) -> bytes:
        while b.tell() < 5:
            recv_buff(sock, b, 256)
        (length,) = struct.unpack("<I", b.getvalue()[1:5])
        while b.tell() < 5 + length:
            recv_buff(sock, b, 256)
        return bytes(b.getvalue()[5:5 + length])
