"""rosservice as a library: service types, providers and calls, as ROS code calls them
(`rosservice.get_service_type('/add_two_ints')`). The `rosservice` command is
kame.cli.rosservice; this module shares its probes and argument filling.

Unlike upstream's call_service, which calls rospy.init_node('rosservice', anonymous=True) (and
so fails in a program that already is a node), kame's calls the service under this process's
node name if it has one, without registering a node otherwise.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from io import BytesIO as BufferType
from optparse import OptionParser
from typing import Any

import rosgraph.names
from kame.cli import rosservice as _command
from kame.cli._tool import ToolError
from kame.cli.rosservice import ID, Tool, _srv_text, arg_summary, load_service_class
from kame.client import clock, core
from kame.client.errors import ROSSerializationException
from kame.client.services import ServiceException, ServiceProxy
from kame.msg.fill import FillError, fill_message_args, printable_message_args
from kame.net.handshake import HandshakeError, read_header, write_header
from kame.net.stream import connect
from kame.node.services import ServiceError, parse_rosrpc
from kame.protocol import tcpros
from kame.rostime import Time

__all__ = ["NAME", "BufferType", "OptionParser", "ROSServiceException", "ROSServiceIOException", "call_service",
           "get_service_args", "get_service_class_by_name", "get_service_headers", "get_service_list",
           "get_service_node", "get_service_type", "get_service_uri", "has_service_args", "rosservice_find",
           "rosservicemain"]


class ROSServiceException(Exception):
    """Base of rosservice's errors."""


class ROSServiceIOException(ROSServiceException):
    """The master or the service could not be reached."""


@contextmanager
def _tool() -> Iterator[Tool]:
    try:
        t = Tool(ID)
    except ToolError as exc:
        raise ROSServiceIOException(str(exc)) from None
    try:
        yield t
    except ToolError as exc:
        raise ROSServiceIOException(str(exc)) from None
    finally:
        t.close()


def get_service_type(service_name: str) -> str | None:
    """The type of the service (`pkg/Srv`), asked of the service itself; None when the master
    does not know it; ROSServiceIOException when it cannot be reached."""
    with _tool() as t:
        return t.type(service_name)


def get_service_class_by_name(service_name: str) -> Any:
    """The class of the service's type; ROSServiceException when it is unknown or cannot load."""
    with _tool() as t:
        service_type = t.type(service_name)
    if not service_type:
        raise ROSServiceException(f"Service [{service_name}] is not available.")
    service_class = load_service_class(service_type)
    if service_class is None:
        package = service_type.partition("/")[0]
        raise ROSServiceException(f"Unable to load type [{service_type}].\nHave you typed 'make' in [{package}]?")
    return service_class


def get_service_list(node: str | None = None, namespace: str | None = None,
                     include_nodes: bool = False) -> list[str] | list[tuple[str, list[str]]]:
    """The services the master knows, sorted; only those of `node` / under `namespace` if given;
    `include_nodes`: (service, [providing node]) pairs."""
    with _tool() as t:
        services = sorted((name, providers) for name, providers in t.services(namespace)
                          if node is None or node in providers)
    if include_nodes:
        return [(name, list(providers)) for name, providers in services]
    return [name for name, _ in services]


def get_service_node(service_name: str) -> str | None:
    """The node providing the service, or None."""
    with _tool() as t:
        return t.provider(service_name)


def get_service_uri(service_name: str) -> str | None:
    """The service's rosrpc:// URI, or None."""
    with _tool() as t:
        return t.uri(service_name)


def call_service(service_name: str, service_args: Sequence[Any], service_class: Any = None) -> tuple[Any, Any]:
    """Call the service with a request filled from `service_args` (as `rosservice call` fills
    it: positional values or one dict; `now`/`auto` stamps); returns (request, response)."""
    if service_class is None:
        service_class = get_service_class_by_name(service_name)
    request = service_class._request_class()
    now = clock.get_rostime() if core.is_initialized() else Time.from_sec(time.time())
    keys: dict[str, Any] = {"now": now}
    try:
        from std_msgs.msg import Header

        keys["auto"] = Header(stamp=now)
    except ImportError:
        pass
    try:
        fill_message_args(request, list(service_args), keys)
    except FillError as exc:
        raise ROSServiceException(
            f"Incompatible arguments to call service:\n{exc}\nProvided arguments are:\n"
            f"{arg_summary(list(service_args))}\n\nService arguments are: [{printable_message_args(request)}]"
        ) from None
    proxy = ServiceProxy(service_name, service_class)
    try:
        return request, proxy(request)
    except ServiceException as exc:
        raise ROSServiceException(str(exc)) from None
    except ROSSerializationException as exc:
        raise ROSServiceException("Unable to send request. One of the fields has an incorrect type:\n"
                                  f"  {exc}\n\nsrv file:\n{_srv_text(service_class._type)}") from None
    finally:
        proxy.close()


# ---------------------------------------------------------------- rosservice's command parts

NAME = "rosservice"


def get_service_headers(service_name: str, service_uri: str) -> dict[str, str]:
    """The TCPROS header service `service_name` at `service_uri` (rosrpc://host:port) answers a
    probe with (its type, md5sum, ...)."""
    try:
        host, port = parse_rosrpc(service_uri)
    except ServiceError:
        raise ROSServiceException(f"service [{service_name}] has an invalid RPC URI [{service_uri}]") from None
    try:
        sock = connect(host, port, timeout=5.0)
    except OSError as exc:
        raise ROSServiceIOException(f"Unable to communicate with service [{service_name}], address "
                                    f"[{service_uri}]") from exc
    try:
        sock.settimeout(5.0)
        write_header(sock, tcpros.service_probe_header_fields(callerid=ID, service=service_name))
        return read_header(sock)
    except (OSError, HandshakeError) as exc:
        raise ROSServiceIOException(f"Unable to communicate with service [{service_name}], address "
                                    f"[{service_uri}]") from exc
    finally:
        sock.close()


def rosservice_find(service_type: str) -> list[str]:
    """The services whose type is `service_type`."""
    with _tool() as t:
        matches = []
        for name, _providers in t.services():
            try:
                found = t.type(name)
            except ToolError:  # a service that does not answer is not a match, as rosservice's
                continue
            if found == service_type:
                matches.append(name)
        return matches


def has_service_args(service_name: str, service_class: Any = None) -> bool:
    """Whether the service's request has fields."""
    name = rosgraph.names.script_resolve_name(NAME, service_name)
    if service_class is None:
        service_class = get_service_class_by_name(name)
    return len(service_class._request_class.__slots__) > 0


def get_service_args(service_name: str) -> str:
    """The request's fields as `rosservice args` prints them."""
    name = rosgraph.names.script_resolve_name(NAME, service_name)
    return printable_message_args(get_service_class_by_name(name)._request_class)


def rosservicemain(argv: Sequence[str] = sys.argv) -> None:
    """The rosservice command on `argv` (the program, then the command); ends the process."""
    sys.exit(_command.main(list(argv)[1:]))
