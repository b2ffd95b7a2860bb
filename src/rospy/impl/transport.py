"""rospy.impl.transport: a connection as rospy's transports describe it (Transport: direction,
name, id, byte and message counts, endpoints), its closed form (DeadTransport) and the
protocol handler interface (ProtocolHandler). rospy.impl.tcpros_base's TCPROSTransport is the
one that carries bytes."""

from __future__ import annotations

import itertools
import threading
from collections.abc import Callable
from typing import Any

__all__ = ["BIDIRECTIONAL", "INBOUND", "OUTBOUND", "DeadTransport", "ProtocolHandler", "Transport"]

INBOUND = "i"
OUTBOUND = "o"
BIDIRECTIONAL = "b"

_ids = itertools.count(1)
_id_lock = threading.Lock()


def _next_id() -> int:
    with _id_lock:
        return next(_ids)


class Transport:
    """A connection's book-keeping; subclasses write_data and say get_transport_info."""

    transport_type = "UNKNOWN"

    def __init__(self, direction: str, name: str = "unnamed") -> None:
        self.name = name
        self.direction = direction
        self.done = False
        self.cleanup_cb: Callable[[Transport], Any] | None = None
        self.endpoint_id = ""
        self.id = _next_id()
        self.stat_bytes = 0
        self.stat_num_msg = 0
        self.local_endpoint: tuple[Any, Any] = (0, 0)
        self.remote_endpoint: tuple[Any, Any] = (0, 0)

    def fileno(self) -> int | None:
        return None

    def set_cleanup_callback(self, cleanup_callback: Callable[[Transport], Any]) -> None:
        self.cleanup_cb = cleanup_callback

    def close(self) -> None:
        self.done = True
        if self.cleanup_cb:
            self.cleanup_cb(self)

    def write_data(self, data: bytes) -> bool:
        raise NotImplementedError(f"{type(self).__name__} carries no data")

    def get_transport_info(self) -> str:
        raise NotImplementedError(f"{type(self).__name__} does not describe itself")


class DeadTransport(Transport):
    """What is left of a closed transport: its id, counts and endpoints."""

    def __init__(self, transport: Transport) -> None:
        super().__init__(transport.direction, transport.name)
        self.transport_type = transport.transport_type
        self.id = transport.id
        self.stat_bytes = transport.stat_bytes
        self.stat_num_msg = transport.stat_num_msg
        self.done = True
        self.endpoint_id = transport.endpoint_id
        self.local_endpoint = transport.local_endpoint
        self.remote_endpoint = transport.remote_endpoint

    def get_transport_info(self) -> str:
        return (f"Closed {self.transport_type} connection on port {self.local_endpoint[1]} "
                f"to [{self.remote_endpoint[0]}:{self.remote_endpoint[1]}]")


class ProtocolHandler:
    """A transport protocol in topic negotiation: which it supports, how a publisher offers it
    and how a subscriber's transport is made."""

    def shutdown(self) -> None:
        return None

    def create_transport(self, topic: str, pub_uri: str, protocol_params: list[Any]) -> tuple[int, str, int]:
        raise NotImplementedError("ProtocolHandler is an interface: its subclass makes transports")

    def supports(self, protocol: str) -> bool:
        return False

    def get_supported(self) -> list[list[str]]:
        return []

    def init_publisher(self, topic: str, protocol: list[Any]) -> tuple[int, str, list[Any]]:
        raise NotImplementedError("ProtocolHandler is an interface: its subclass offers the protocol")
