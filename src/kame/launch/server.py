"""The roslaunch server: the XML-RPC API a running roslaunch (or roscore) offers the tools.

Rules (ros1-interop spec §11, roslaunch's server.py):
- Methods take no caller_id, as roslaunch's handler: `get_pid` -> [1, "", pid];
  `list_processes` -> [1, "processes on parent machine", [running, dead]], each a list of
  [process name, spawn count]; `process_info(name)` -> [1, "process info", {...}] or
  [-1, "no process by that name", {}]; `get_node_names` -> [1, "node names", names], which
  are, as roslaunch's process monitor gives them, the running processes' names.
- Its URI is announced as `started roslaunch server http://<host>:<port>/` and stored as
  `/roslaunch/uris/host_<host>__<port>` (roswtf checks those servers are still there), and
  deleted when the launch ends (kame.launch.runner's withdraw_server; roslaunch leaves it).
- RpcHandlerServer is the same server calling any handler by method name (roslaunch.server
  serves roslaunch's handler objects on it).
- The processes are read through a callable, at call time, from whatever runs them (the
  launch supervisor, or roscore's own core nodes): the server owns no process state.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Callable
from types import MethodType
from typing import Any

from kame.arity import accepts
from kame.net.address import uri_host
from kame.net.rpc_server import RpcServer
from kame.protocol.xmlrpc import Fault, MalformedError, decode_request, encode_fault, encode_response

__all__ = ["LaunchServer", "ProcessState", "RpcHandlerServer", "uri_param"]

log = logging.getLogger("kame.launch.server")


class ProcessState:
    """What the server says of one launched process."""

    __slots__ = ("alive", "args", "exit_code", "name", "node_name", "required", "respawn", "spawn_count")

    def __init__(self, name: str, spawn_count: int, alive: bool, *, node_name: str | None = None,
                 args: list[str] | None = None, respawn: bool = False, required: bool = False,
                 exit_code: int | None = None) -> None:
        self.name = name  # roslaunch's process name: "talker-2", "rosout-1", "master"
        self.spawn_count = spawn_count
        self.alive = alive
        self.node_name = node_name  # the ROS name, for get_node_names
        self.args = args or []
        self.respawn = respawn
        self.required = required
        self.exit_code = exit_code

    def info(self) -> dict[str, object]:
        info: dict[str, object] = {"name": self.name, "spawn_count": self.spawn_count, "alive": self.alive,
                                   "args": list(self.args), "respawn": self.respawn, "required": self.required}
        if self.exit_code is not None:
            info["exit_code"] = self.exit_code
        return info


def uri_param(host: str, port: int) -> str:
    """`/roslaunch/uris/host_<host, lower-cased, non-alphanumerics as _>__<port>`."""
    return "/roslaunch/uris/host_" + "".join(c if c.isalnum() else "_" for c in host.lower()) + f"__{port}"


class RpcHandlerServer:
    """An XML-RPC server calling, for each method, what `lookup` returns for its name (None: not
    supported); the answer is sent as returned. A failing method answers a fault, the server stays."""

    def __init__(self, bind_host: str, advertised_host: str,
                 lookup: Callable[[str], Callable[..., Any] | None]) -> None:
        self._lookup = lookup
        self._rpc = RpcServer(bind_host, 0, self._handle, name="roslaunch-server")
        self.host = advertised_host
        self.port = self._rpc.port
        self.uri = f"http://{uri_host(advertised_host)}:{self.port}/"

    def start(self) -> None:
        self._rpc.start()

    def close(self) -> None:
        self._rpc.close()

    @property
    def param(self) -> str:
        return uri_param(self.host, self.port)

    def _handle(self, body: bytes) -> bytes:
        try:
            method, params = decode_request(body)
        except (MalformedError, Fault) as exc:
            return encode_fault(1, f"<class 'Exception'>:malformed request: {exc}")
        handler = self._lookup(method)
        if handler is None:
            return encode_fault(1, f"<class 'Exception'>:method \"{method}\" is not supported")
        if not accepts(handler, len(params)):
            return encode_fault(1, f"<class 'TypeError'>:{method}: wrong number or type of arguments")
        try:
            return encode_response(handler(*params))
        except Exception as exc:  # a bug in one method must not end the server
            log.exception("roslaunch server: %s failed", method)
            return encode_fault(1, f"<class 'Exception'>:{exc}")


class LaunchServer(RpcHandlerServer):
    def __init__(self, bind_host: str, advertised_host: str, processes: Callable[[], list[ProcessState]]) -> None:
        self._processes = processes
        super().__init__(bind_host, advertised_host, self._method)

    def _method(self, name: str) -> Callable[..., list[object]] | None:
        handler = _METHODS.get(name)
        return None if handler is None else MethodType(handler, self)

    def _get_pid(self) -> list[object]:
        return [1, "", os.getpid()]

    def _list_processes(self) -> list[object]:
        states = self._processes()
        running = [[p.name, p.spawn_count] for p in states if p.alive]
        dead = [[p.name, p.spawn_count] for p in states if not p.alive]
        return [1, "processes on parent machine", [running, dead]]

    def _process_info(self, name: str) -> list[object]:
        for state in self._processes():
            if state.name == name:
                return [1, "process info", state.info()]
        return [-1, "no process by that name", {}]

    def _get_node_names(self) -> list[object]:
        return [1, "node names", [p.name for p in self._processes() if p.alive]]


_METHODS: dict[str, Callable[..., list[object]]] = {
    "get_pid": LaunchServer._get_pid,
    "list_processes": LaunchServer._list_processes,
    "process_info": LaunchServer._process_info,
    "get_node_names": LaunchServer._get_node_names,
}
