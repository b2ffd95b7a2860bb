"""rosgraph.xmlrpc: ROS's XML-RPC server for a handler object (XmlRpcNode), over kame's.

`XmlRpcNode(port, handler)` serves the handler's public methods (and system.multicall) on
kame's threaded RPC server (kame.net.rpc_server): `start()` binds, sets `uri` (ROS_IP or
ROS_HOSTNAME, else the host name, else the local address, as rosgraph chooses), calls
`handler._ready(uri)` and serves on the server's own threads; `shutdown(reason)` calls
`handler._shutdown(reason)` and closes them. `run()` is `start()` that blocks until shutdown.
`ServerProxy` is xmlrpc.client's calling style (`proxy.getPid(caller_id)`) over kame's
XML-RPC client (kame.net.server_proxy), faults raised as xmlrpc.client.Fault.
The standard library's servers rosgraph builds on (ThreadingXMLRPCServer, ...) are here for
code that serves with them itself (kame.net.xmlrpc_servers).
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable
from typing import Any

from kame.net.interfaces import hostname
from kame.net.rpc_server import RpcServer
from kame.net.server_proxy import ServerProxy
from kame.net.xmlrpc_servers import (
    ForkingXMLRPCServer,
    SilenceableXMLRPCRequestHandler,
    SimpleXMLRPCRequestHandler,
    SimpleXMLRPCServer,
    ThreadingXMLRPCServer,
)
from kame.protocol.xmlrpc import Fault, MalformedError, decode_request, encode_fault, encode_response

from . import network

__all__ = ["ForkingXMLRPCServer", "ServerProxy", "SilenceableXMLRPCRequestHandler", "SimpleXMLRPCRequestHandler",
           "SimpleXMLRPCServer", "ThreadingXMLRPCServer", "XmlRpcHandler", "XmlRpcNode", "isstring"]

log = logging.getLogger("xmlrpc")


def isstring(s: object) -> bool:
    return isinstance(s, str)


class XmlRpcHandler:
    """Base of the handlers an XmlRpcNode serves: their public methods are the XML-RPC methods."""

    def _ready(self, uri: str) -> None:
        """Called with the server's URI once it listens."""

    def _shutdown(self, reason: str) -> None:
        """Called when the node shuts down."""


def _unsupported(name: str) -> str:
    return f'<class \'Exception\'>:method "{name}" is not supported'


class XmlRpcNode:
    """An XML-RPC server for `rpc_handler` on `port` (0: any free port)."""

    def __init__(self, port: int | str = 0, rpc_handler: Any = None,
                 on_run_error: Callable[[Exception], None] | None = None) -> None:
        self.handler = rpc_handler
        self.uri: str | None = None
        self.server: RpcServer | None = None
        self.port: int | None = int(port) if port else 0
        self.is_shutdown = False
        self.on_run_error = on_run_error
        self._stopped = threading.Event()

    def shutdown(self, reason: str) -> None:
        """Stop serving, telling the handler why."""
        self.is_shutdown = True
        server, handler = self.server, self.handler
        self.handler = self.server = self.port = self.uri = None
        if server is not None:
            if handler is not None:
                handler._shutdown(reason)
            server.close()
        self._stopped.set()

    def start(self) -> None:
        """Bind and serve (on the server's threads); an error goes to on_run_error, or is raised."""
        try:
            self._run_init()
        except Exception as exc:
            if self.is_shutdown:
                return
            if self.on_run_error is None:
                raise
            self.on_run_error(exc)

    def run(self) -> None:
        """start(), then wait until shutdown."""
        self.start()
        if self.server is not None:
            self._stopped.wait()

    def set_uri(self, uri: str) -> None:
        """The hook subclasses use to learn the URI before the handler does."""
        self.uri = uri

    def _run_init(self) -> None:
        bind_address = network.get_bind_address()
        port = self.port or 0
        log.info("XML-RPC server binding to %s:%d", bind_address, port)
        try:
            self.server = RpcServer(bind_address, port, self._handle, name="rosgraph-xmlrpc")
        except OSError as exc:
            if exc.errno == 98:  # EADDRINUSE
                msg = f"ERROR: Unable to start XML-RPC server, port {port} is already in use"
            else:
                msg = f"ERROR: Unable to start XML-RPC server: {exc.strerror}"
            log.error(msg)
            print(msg)
            raise
        self.port = self.server.port
        self.set_uri(f"http://{self._advertised_host()}:{self.port}/")
        log.info("Started XML-RPC server [%s]", self.uri)
        self.server.start()
        if self.handler is not None and self.uri is not None:
            self.handler._ready(self.uri)

    @staticmethod
    def _advertised_host() -> str:
        override = network.get_address_override()
        if override:
            return override
        name = hostname()
        if name and name != "localhost" and not name.startswith("127.") and name != "::":
            return name
        return network.get_local_address()

    def _method(self, name: str) -> Callable[..., Any] | None:
        if name == "system.multicall":
            return self._multicall
        if name.startswith("_") or "." in name:
            return None
        method = getattr(self.handler, name, None)
        return method if callable(method) else None

    def _multicall(self, calls: list[dict[str, Any]]) -> list[Any]:
        results: list[Any] = []
        for call in calls:
            name = str(call.get("methodName", ""))
            method = self._method(name)
            if method is None:
                results.append({"faultCode": 1, "faultString": _unsupported(name)})
                continue
            try:
                results.append([method(*call.get("params", []))])
            except Exception as exc:  # one failing call is that call's fault, as SimpleXMLRPCServer
                results.append({"faultCode": 1, "faultString": f"{type(exc)}:{exc}"})
        return results

    def _handle(self, body: bytes) -> bytes:
        try:
            name, params = decode_request(body)
        except (MalformedError, Fault) as exc:
            return encode_fault(1, f"<class 'Exception'>:malformed request: {exc}")
        method = self._method(name)
        if method is None:
            return encode_fault(1, _unsupported(name))
        try:
            return encode_response(method(*params))
        except Exception as exc:  # as SimpleXMLRPCServer: the caller gets a fault, the server stays
            log.debug("XML-RPC method %s failed", name, exc_info=True)
            return encode_fault(1, f"{type(exc)}:{exc}")
