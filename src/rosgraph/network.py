"""rosgraph.network: which address a ROS process uses, URIs, and the TCPROS handshake header.

Over kame.net.address (the override, bind and advertised-host rules every kame process follows)
and kame.protocol.header (the header codec). The socket helpers
read_/write_ros_handshake_header are not offered: kame's own connections do that in kame.net.
"""

from __future__ import annotations

import logging
import os
import struct
import sys
from collections.abc import Mapping
from io import BytesIO
from typing import IO, Any
from urllib.parse import urlparse

from kame.net import address as _address
from kame.net.handshake import HandshakeError, read_header_and_rest
from kame.net.interfaces import local_addresses
from kame.protocol.header import TcprosError, decode_header_fields, encode_header

from .rosenv import ROS_HOSTNAME, ROS_IP, ROS_IPV6

__all__ = [
    "ROS_HOSTNAME",
    "ROS_IP",
    "ROS_IPV6",
    "SIOCGIFADDR",
    "SIOCGIFCONF",
    "BytesIO",
    "ROSHandshakeException",
    "create_local_xmlrpc_uri",
    "decode_ros_handshake_header",
    "encode_ros_handshake_header",
    "get_address_override",
    "get_bind_address",
    "get_host_name",
    "get_local_address",
    "get_local_addresses",
    "is_local_address",
    "logger",
    "parse_http_host_and_port",
    "python3",
    "read_ros_handshake_header",
    "use_ipv6",
    "write_ros_handshake_header",
]


SIOCGIFCONF = 0x8912  # the ioctls rosgraph lists interfaces with (kame asks kame.net.interfaces)
SIOCGIFADDR = 0x8915
python3 = 1
logger = logging.getLogger("rosgraph.network")


class ROSHandshakeException(Exception):
    """A malformed TCPROS connection header."""


def read_ros_handshake_header(sock: Any, b: IO[bytes], buff_size: int) -> dict[str, str]:
    """A connection header read off blocking `sock`; what came after it is left in buffer `b`.
    `buff_size` is unused: kame reads the header as it arrives."""
    try:
        fields, rest = read_header_and_rest(sock)
    except HandshakeError as exc:
        raise ROSHandshakeException(f"connection from sender terminated before handshake header received. "
                                    f"{b.tell()} bytes were received. Please check sender for additional details."
                                    if "closed" in str(exc) else str(exc)) from exc
    b.seek(0)
    b.truncate()
    b.write(rest)
    return fields


def write_ros_handshake_header(sock: Any, header: Mapping[str | bytes, str | bytes]) -> int:
    """Send a connection header on blocking `sock`; the bytes sent."""
    data = encode_ros_handshake_header(header)
    sock.sendall(data)
    return len(data)


def parse_http_host_and_port(url: str) -> tuple[str, int]:
    """(host, port) of an http URL, port 80 when absent; ValueError without scheme or host."""
    if not url:
        raise ValueError("not a valid URL")
    parts = urlparse(url)
    if not parts.scheme or not parts.hostname:
        raise ValueError("not a valid URL")
    return parts.hostname, parts.port or 80


def get_address_override() -> str | None:
    """The first `__hostname:=`/`__ip:=` argument in sys.argv, else ROS_HOSTNAME, else ROS_IP
    (warning on stderr about a malformed value), else None."""
    for arg in sys.argv:
        if arg.startswith(("__hostname:=", "__ip:=")):
            parts = arg.split(":=")
            if len(parts) != 2:
                raise ValueError(f"invalid ROS command-line remapping argument '{arg}'")
            return parts[1]
    return _address.environment_override(os.environ)


def use_ipv6() -> bool:
    return _address.use_ipv6(os.environ)


def get_local_addresses() -> list[str]:
    """This machine's addresses (IPv6 first when ROS_IPV6=on); not affected by overrides."""
    return local_addresses(use_ipv6())


def is_local_address(hostname: str) -> bool:
    """True when `hostname` resolves to a loopback address or one of this machine's."""
    return _address.is_local_address(hostname, use_ipv6())


def get_local_address() -> str:
    """The override, else this machine's address (the only one, else the first not loopback)."""
    return get_address_override() or _address.local_address(use_ipv6())


def get_bind_address(address: str | None = None) -> str:
    """Where to bind: a loopback `address` (default: the override) binds loopback only."""
    return _address.bind_host(get_address_override() if address is None else address, use_ipv6())


def get_host_name() -> str:
    """The host name to put in URIs: the override, else the host name unless it is loopback,
    else get_local_address()."""
    return _address.advertised_host(get_address_override(), use_ipv6())


def create_local_xmlrpc_uri(port: int) -> str:
    return f"http://{_address.uri_host(get_host_name())}:{port}/"


def decode_ros_handshake_header(header_str: bytes) -> dict[str, str]:
    """A whole serialized header (4-byte length first) as {key: value}."""
    (size,) = struct.unpack("<I", header_str[0:4])
    size += 4
    if size > len(header_str):
        raise ROSHandshakeException(f"Incomplete header. Expected {size + 4} bytes but only have {len(header_str)}")
    try:
        fields = decode_header_fields(header_str[4:size])
    except TcprosError as exc:
        raise ROSHandshakeException(str(exc)) from exc
    return {key.strip(): value for key, value in fields.items()}


def encode_ros_handshake_header(header: Mapping[str | bytes, str | bytes]) -> bytes:
    """The header serialized as rosgraph does: fields sorted by key, length-prefixed."""
    def text(value: str | bytes) -> str:
        return value.decode("utf-8") if isinstance(value, bytes) else value

    fields = {text(key): value for key, value in header.items()}
    return encode_header(dict(sorted(fields.items())))
