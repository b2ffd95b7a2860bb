"""The standard library's XML-RPC servers as rosgraph.xmlrpc names them, for ROS code that
builds its own server on them (kame's own XML-RPC serving is kame.net.rpc_server's).

`ThreadingXMLRPCServer(addr, log_requests)` serves each request on a thread of its own (rosgraph's:
daemon threads, the address reusable at once, errors to the `xmlrpc` logger, IPv6 when
ROS_IPV6=on); `ForkingXMLRPCServer` forks per request; `SilenceableXMLRPCRequestHandler` logs no
requests and speaks HTTP/1.1 (rosgraph keeps HTTP/1.0 on Linux kernels before 4.16, whose
loopback made it slow; kame supports none of those).
"""

from __future__ import annotations

import logging
import os
import socket
import socketserver
import traceback
from typing import Any
from xmlrpc.server import SimpleXMLRPCRequestHandler, SimpleXMLRPCServer

__all__ = ["ForkingXMLRPCServer", "SilenceableXMLRPCRequestHandler", "SimpleXMLRPCRequestHandler",
           "SimpleXMLRPCServer", "ThreadingXMLRPCServer"]


class SilenceableXMLRPCRequestHandler(SimpleXMLRPCRequestHandler):
    protocol_version = "HTTP/1.1"

    def log_message(self, format: str, *args: Any) -> None:
        """Requests are not logged."""


class ThreadingXMLRPCServer(socketserver.ThreadingMixIn, SimpleXMLRPCServer):
    """A SimpleXMLRPCServer answering each request on a thread of its own."""

    daemon_threads = True
    allow_reuse_address = True

    def __init__(self, addr: tuple[str, int], log_requests: bool = True) -> None:
        self.request_queue_size = min(socket.SOMAXCONN, 128)
        if os.environ.get("ROS_IPV6") == "on":
            self.address_family = socket.AF_INET6
        SimpleXMLRPCServer.__init__(self, addr, SilenceableXMLRPCRequestHandler, log_requests)

    def handle_error(self, request: Any, client_address: Any) -> None:
        """To the `xmlrpc` logger, not stderr."""
        logging.getLogger("xmlrpc").error(traceback.format_exc())


class ForkingXMLRPCServer(socketserver.ForkingMixIn, SimpleXMLRPCServer):
    """A SimpleXMLRPCServer answering each request in a child process."""

    def __init__(self, addr: tuple[str, int], request_handler: type[SimpleXMLRPCRequestHandler] =
                 SilenceableXMLRPCRequestHandler, log_requests: bool = True) -> None:
        SimpleXMLRPCServer.__init__(self, addr, request_handler, log_requests)
