"""xmlrpc.client's calling convention over kame's XML-RPC client (kame.net.xmlrpc_client), for the
compatibility packages whose ROS originals hand programs a ServerProxy (roslaunch's Master.get())
or a MultiCall.

- `ServerProxy(uri).method(*params)` (dotted names too: `proxy.system.listMethods()`) returns the
  decoded answer; a fault raises kame.protocol.xmlrpc.Fault, a failed call XmlRpcTransportError
  (an OSError, as the stdlib's socket errors are).
- Unlike the stdlib's, whose calls may wait for ever, each call is bounded by `timeout` (60 s
  unless given): a launch child's `launch` call waits for its nodes to start, so it is generous.
- `MultiCall(proxy)`: calls are queued, then sent as one `system.multicall` when it is called;
  the answers come back in order, a fault raised when its turn comes, as the stdlib's.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from typing import Any

from kame.net.xmlrpc_client import XmlRpcProxy
from kame.protocol.xmlrpc import Fault, Value

__all__ = ["DEFAULT_TIMEOUT", "MultiCall", "ServerProxy"]

DEFAULT_TIMEOUT = 60.0


class _Method:
    """`proxy.name` (or `proxy.a.b`): calling it calls the method of that name."""

    def __init__(self, send: Callable[[str, Sequence[Any]], Any], name: str) -> None:
        self._send = send
        self._name = name

    def __getattr__(self, name: str) -> _Method:
        return _Method(self._send, f"{self._name}.{name}")

    def __call__(self, *params: Any) -> Any:
        return self._send(self._name, params)


class ServerProxy:
    """Calls the XML-RPC server at `uri` (one kept-alive connection, calls serialised)."""

    def __init__(self, uri: str, timeout: float = DEFAULT_TIMEOUT) -> None:
        self.__uri = uri
        self.__proxy = XmlRpcProxy(uri, timeout=timeout)

    def __send(self, name: str, params: Sequence[Any]) -> Value:
        return self.__proxy.call(name, *params)

    def __getattr__(self, name: str) -> _Method:
        if name.startswith("__"):
            raise AttributeError(name)
        return _Method(self.__send, name)

    def __call__(self, attr: str) -> Callable[[], None]:
        """`proxy("close")()` closes the connection, as with the stdlib's."""
        if attr == "close":
            return self.__proxy.close
        raise AttributeError(f"Attribute {attr!r} not found")

    def __enter__(self) -> ServerProxy:
        return self

    def __exit__(self, *exc: object) -> None:
        self.__proxy.close()

    def __repr__(self) -> str:
        return f"<ServerProxy for {self.__uri}>"


class MultiCall:
    """Queues calls to `server`'s methods, sent together when called."""

    def __init__(self, server: ServerProxy) -> None:
        self.__server = server
        self.__calls: list[dict[str, Any]] = []

    def __queue(self, name: str, params: Sequence[Any]) -> None:
        self.__calls.append({"methodName": name, "params": list(params)})

    def __getattr__(self, name: str) -> _Method:
        if name.startswith("__"):
            raise AttributeError(name)
        return _Method(self.__queue, name)

    def __call__(self) -> Iterator[Any]:
        answers = self.__server.system.multicall(self.__calls)
        return _results(answers)

    def __repr__(self) -> str:
        return f"<MultiCall at {id(self):#x}>"


def _results(answers: Any) -> Iterator[Any]:
    for answer in answers:
        if isinstance(answer, dict):
            raise Fault(answer["faultCode"], answer["faultString"])
        yield answer[0]
