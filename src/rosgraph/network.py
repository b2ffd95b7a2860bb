"""rosgraph.network: which address a ROS process uses, URIs, and the TCPROS handshake header.

Over kame.net (addresses) and kame.protocol.header (the header codec). The socket helpers
read_/write_ros_handshake_header are not offered: kame's own connections do that in kame.net.
"""

from __future__ import annotations

import os
import struct
import sys
from collections.abc import Mapping
from urllib.parse import urlparse

from kame.net.interfaces import hostname, local_addresses, resolve
from kame.protocol.header import TcprosError, decode_header_fields, encode_header

from .rosenv import ROS_HOSTNAME, ROS_IP, ROS_IPV6

__all__ = ["ROSHandshakeException", "create_local_xmlrpc_uri", "decode_ros_handshake_header",
           "encode_ros_handshake_header", "get_address_override", "get_bind_address", "get_host_name",
           "get_local_address", "get_local_addresses", "is_local_address", "parse_http_host_and_port", "use_ipv6"]


class ROSHandshakeException(Exception):
    """A malformed TCPROS connection header."""


def parse_http_host_and_port(url: str) -> tuple[str, int]:
    """(host, port) of an http URL, port 80 when absent; ValueError without scheme or host."""
    if not url:
        raise ValueError("not a valid URL")
    parts = urlparse(url)
    if not parts.scheme or not parts.hostname:
        raise ValueError("not a valid URL")
    return parts.hostname, parts.port or 80


def _warn(message: str) -> None:
    sys.stderr.write(message + "\n")


def get_address_override() -> str | None:
    """`__hostname:=`/`__ip:=`, else ROS_HOSTNAME, else ROS_IP (warning on stderr about a value
    with a protocol or port in it, as rosgraph does), else None."""
    for arg in sys.argv:
        if arg.startswith(("__hostname:=", "__ip:=")):
            parts = arg.split(":=")
            if len(parts) != 2:
                raise ValueError(f"invalid ROS command-line remapping argument '{arg}'")
            return parts[1]
    if ROS_HOSTNAME in os.environ:
        name = os.environ[ROS_HOSTNAME]
        parsed = urlparse(name)
        if name == "":
            _warn("invalid ROS_HOSTNAME (an empty string)")
        elif parsed.scheme:
            _warn("invalid ROS_HOSTNAME (protocol " + ("and port " if parsed.port else "") + "should not be included)")
        elif ":" in name:
            _warn("invalid ROS_HOSTNAME (port should not be included)")
        return name
    if ROS_IP in os.environ:
        ip = os.environ[ROS_IP]
        if ip == "":
            _warn("invalid ROS_IP (an empty string)")
        elif "://" in ip:
            _warn("invalid ROS_IP (protocol should not be included)")
        elif "." in ip and ip.rfind(":") > ip.rfind("."):
            _warn("invalid ROS_IP (port should not be included)")
        elif "." not in ip and ":" not in ip:
            _warn("invalid ROS_IP (must be a valid IPv4 or IPv6 address)")
        return ip
    return None


def use_ipv6() -> bool:
    return os.environ.get(ROS_IPV6) == "on"


def get_local_addresses() -> list[str]:
    """This machine's addresses (IPv6 first when ROS_IPV6=on); not affected by overrides."""
    return local_addresses(use_ipv6())


def is_local_address(hostname: str) -> bool:
    """True when `hostname` resolves to a loopback address or one of this machine's."""
    found = resolve(hostname, use_ipv6())
    if found is None:
        return False
    local = {"localhost", *get_local_addresses()}
    return any(ip.startswith("127.") or ip == "::1" for ip in found) or bool(set(found) & local)


def get_local_address() -> str:
    """The override, else this machine's address (the only one, else the first not loopback)."""
    override = get_address_override()
    if override:
        return override
    addresses = get_local_addresses()
    if len(addresses) == 1:
        return addresses[0]
    for address in addresses:
        if not address.startswith("127.") and address != "::1":
            return address
    return "::1" if use_ipv6() else "127.0.0.1"


def get_bind_address(address: str | None = None) -> str:
    """Where to bind: a loopback `address` (default: the override) binds loopback only."""
    if address is None:
        address = get_address_override()
    if address and (address == "localhost" or address.startswith("127.") or address == "::1"):
        if use_ipv6():
            return "::1"
        return address if address.startswith("127.") else "127.0.0.1"
    return "::" if use_ipv6() else "0.0.0.0"


def get_host_name() -> str:
    """The host name to put in URIs: the override, else the host name unless it is loopback,
    else get_local_address()."""
    override = get_address_override()
    if override:
        return override
    name = hostname()
    if not name or name == "localhost" or name.startswith("127."):
        return get_local_address()
    return name


def create_local_xmlrpc_uri(port: int) -> str:
    host = get_host_name()
    if ":" in host:  # an IPv6 address
        host = f"[{host}]"
    return f"http://{host}:{port}/"


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
