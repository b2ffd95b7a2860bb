"""xmlrpc.client's calling style over kame's XML-RPC client, for the ROS facades that hand out
such proxies (rosgraph.masterapi's `handle`, rosgraph.impl.graph's, rosnode's ServerProxy).

`ServerProxy(uri).getPid("/me")` calls through kame.net.xmlrpc_client.XmlRpcProxy; dotted
names reach dotted methods (`proxy.system.multicall(...)`); a fault raises xmlrpc.client.Fault,
as the stdlib's proxy does, so code that catches it keeps working. Each call waits `timeout`
seconds (default: socket.getdefaulttimeout(), read when the proxy is made, else 10 s).
`Fault` and `Binary` are xmlrpc.client's, the names ROS modules import from it.
"""

from __future__ import annotations

import socket
from collections.abc import Callable
from typing import Any
from xmlrpc.client import Binary, Fault

from kame.net.xmlrpc_client import XmlRpcProxy
from kame.protocol.xmlrpc import Fault as KameFault

__all__ = ["Binary", "Fault", "ServerProxy"]

DEFAULT_TIMEOUT = 10.0


class _Method:
    def __init__(self, send: Callable[..., Any], name: str) -> None:
        self._send = send
        self._name = name

    def __getattr__(self, name: str) -> _Method:
        return _Method(self._send, f"{self._name}.{name}")

    def __call__(self, *args: Any) -> Any:
        return self._send(self._name, *args)


class ServerProxy:
    """A remote XML-RPC server whose methods are attributes; an unreachable server raises OSError."""

    def __init__(self, uri: str, *args: Any, timeout: float | None = None, **kwargs: Any) -> None:
        if timeout is None:
            timeout = socket.getdefaulttimeout()
        self._proxy = XmlRpcProxy(uri, timeout=DEFAULT_TIMEOUT if timeout is None else timeout)

    def _call(self, method: str, *params: Any) -> Any:
        try:
            return self._proxy.call(method, *params)
        except KameFault as fault:
            raise Fault(fault.code, fault.message) from None

    def __getattr__(self, name: str) -> _Method:
        if name.startswith("__"):
            raise AttributeError(name)
        return _Method(self._call, name)

    def __call__(self, attr: str) -> Any:
        if attr == "close":  # xmlrpc.client's way to close the connection
            return self._proxy.close
        raise AttributeError(f"Attribute {attr!r} not found")

    def __repr__(self) -> str:
        return f"<ServerProxy for {self._proxy.uri}>"
