"""The master's XML-RPC API as a node calls it: `[code, message, value]` unwrapped.

Every call carries the node's caller_id. A code other than 1 raises MasterError with the
master's text; transport failures raise OSError (the master is not reachable).
"""

from __future__ import annotations

from typing import Any

from kame.net.xmlrpc_client import XmlRpcProxy

SUCCESS = 1


class MasterError(Exception):
    """The master answered with an error or failure code."""

    def __init__(self, code: int, message: str) -> None:
        super().__init__(message)
        self.code = code
        self.message = message


def unwrap(result: Any, method: str) -> Any:
    if not isinstance(result, list) or len(result) != 3 or not isinstance(result[0], int):
        raise MasterError(-1, f"malformed answer to {method}: {result!r}")
    code, message, value = result
    if code != SUCCESS:
        raise MasterError(code, str(message))
    return value


class MasterProxy:
    def __init__(self, uri: str, caller_id: str, timeout: float = 10.0) -> None:
        self.uri = uri
        self.caller_id = caller_id
        self._proxy = XmlRpcProxy(uri, timeout)

    def call(self, method: str, *args: object, timeout: float | None = None) -> Any:
        return unwrap(self._proxy.call(method, self.caller_id, *args, timeout=timeout), method)

    def call_raw(self, method: str, *args: object, timeout: float | None = None) -> Any:
        """The whole [code, message, value] answer (hasParam, searchParam read it)."""
        return self._proxy.call(method, self.caller_id, *args, timeout=timeout)

    @property
    def last_date(self) -> str | None:
        """The Date header of the last answer: the clock of the server's machine, to the second."""
        return self._proxy.last_date

    def close(self) -> None:
        self._proxy.close()
