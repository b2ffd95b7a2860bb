"""roslaunch.server: the XML-RPC server of a roslaunch, as roslaunch's API names it, on kame's
(kame.launch.server). A handler object answers the calls: each public method is an XML-RPC
method of that name (get_pid, list_processes, process_info, get_node_names; the parent's
register, list_children, process_died, log), reading the processes from a process monitor `pm`
(any object with roslaunch's ProcessMonitor methods: get_process_names_with_spawn_count,
get_process, get_active_names).

kame's own roslaunch runs kame's server directly, and starts the nodes of other machines over
its SSH connection rather than through a child roslaunch calling back: the child side
(ROSLaunchChildHandler, ROSLaunchChildNode, whose `launch` runs launch XML sent by the parent)
has nothing of kame's to stand on and is not here.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Callable
from typing import Any

from kame.launch.server import RpcHandlerServer
from kame.launch.supervisor import say, say_bold, say_error
from kame.net.address import host_addresses
from rosgraph_msgs.msg import Log
from roslaunch.core import RLException
from roslaunch.pmon import ProcessListener

__all__ = ["ChildROSLaunchProcess", "ProcessListener", "ROSLaunchBaseHandler", "ROSLaunchNode",
           "ROSLaunchParentHandler", "ROSLaunchParentNode"]

Answer = tuple[int, str, Any]


class ChildROSLaunchProcess:
    """A roslaunch child on another machine, as the parent knows it: its URI once it registers."""

    def __init__(self, name: str, args: list[Any], env: dict[str, str]) -> None:
        self.name = name
        self.args = args
        self.env = env
        self.uri: str | None = None

    def set_uri(self, uri: str) -> None:
        self.uri = uri


class ROSLaunchBaseHandler:
    """The calls every roslaunch server answers, over the process monitor `pm`."""

    def __init__(self, pm: Any) -> None:
        self.pm = pm
        self.logger = logging.getLogger("roslaunch.server")
        if self.pm is None:
            raise RLException("cannot create xmlrpc handler: pm is not initialized")

    def list_processes(self) -> Answer:
        """[[(name, spawn count) running], [(name, spawn count) dead]]."""
        return 1, "processes on parent machine", self.pm.get_process_names_with_spawn_count()

    def process_info(self, process_name: str) -> Answer:
        process = self.pm.get_process(process_name)
        if process is None:
            return -1, "no process by that name", {}
        return 1, "process info", process.get_info()

    def get_pid(self) -> Answer:
        pid = os.getpid()
        return 1, str(pid), pid

    def get_node_names(self) -> Answer:
        if self.pm is None:
            return 0, "uninitialized", []
        return 1, "node names", self.pm.get_active_names()

    def _shutdown(self, reason: str) -> Answer:
        return 1, "", 1


class ROSLaunchParentHandler(ROSLaunchBaseHandler):
    """The parent roslaunch's calls: children registering, remote processes dying, their logs."""

    def __init__(self, pm: Any, child_processes: dict[str, ChildROSLaunchProcess],
                 listeners: list[ProcessListener]) -> None:
        super().__init__(pm)
        self.child_processes = child_processes
        self.listeners = listeners

    def register(self, client: str, uri: str) -> Answer:
        if client not in self.child_processes:
            self.logger.error("Unknown child [%s] registered with server", client)
            return -1, f"unknown child [{client}]", 0
        self.logger.info("child [%s] registered with server, uri[%s]", client, uri)
        self.child_processes[client].set_uri(uri)
        return 1, "registered", 1

    def list_children(self) -> Answer:
        """The URIs of the children that registered."""
        return 1, "roslaunch children", [c.uri for c in self.child_processes.values() if c.uri is not None]

    def process_died(self, process_name: str, exit_code: int) -> Answer:
        for listener in self.listeners:
            try:
                listener.process_died(process_name, exit_code)
            except Exception:  # one listener's bug must not keep the others from hearing
                self.logger.exception("process listener failed on %s", process_name)
        return 1, "", 0

    def log(self, client: str, level: int, message: str) -> Answer:
        """A child's log line, printed as roslaunch prints its own (errors in red)."""
        if level >= Log.ERROR:
            say_error(f"[{client}]: {message}")
        elif "started with pid" in message:
            say_bold(f"[{client}]: {message}")
        else:
            say(f"[{client}]: {message}")
        return 1, "", 1


class ROSLaunchNode:
    """The XML-RPC server of a handler: every public method of `handler` is a method of the API."""

    def __init__(self, handler: ROSLaunchBaseHandler) -> None:
        self.handler = handler
        self.uri: str | None = None
        self.port: int | None = None
        self._server: RpcHandlerServer | None = None

    def _lookup(self, name: str) -> Callable[..., Any] | None:
        method = getattr(self.handler, name, None) if not name.startswith("_") else None
        return method if callable(method) else None

    def start(self) -> None:
        """Serve on a free port on this host's address (ROS_IP/ROS_HOSTNAME as nodes do)."""
        host = host_addresses(os.environ)
        try:
            self._server = RpcHandlerServer(host.bind, host.advertised, self._lookup)
        except OSError as exc:
            raise RLException(f"XML-RPC initialization failed: {exc}") from None
        self._server.start()
        self.uri, self.port = self._server.uri, self._server.port
        say_bold(f"started roslaunch server {self.uri}")

    def shutdown(self, reason: str) -> None:
        """Stop serving; `uri` and `port` are None again."""
        if self._server is not None:
            self.handler._shutdown(reason)
            self._server.close()
            self._server = None
            self.uri = self.port = None


class ROSLaunchParentNode(ROSLaunchNode):
    """The parent roslaunch's server, for the launch `rosconfig` run by the process monitor `pm`."""

    def __init__(self, rosconfig: Any, pm: Any) -> None:
        self.rosconfig = rosconfig
        self.listeners: list[ProcessListener] = []
        self.child_processes: dict[str, ChildROSLaunchProcess] = {}
        if pm is None:
            raise RLException("cannot create parent node: pm is not initialized")
        super().__init__(ROSLaunchParentHandler(pm, self.child_processes, self.listeners))

    def add_child(self, name: str, p: ChildROSLaunchProcess) -> None:
        """Expect a child named `name` to register."""
        self.child_processes[name] = p

    def add_process_listener(self, l: ProcessListener) -> None:  # noqa: E741 (upstream's name)
        """Hear of the children's processes dying (before they start)."""
        self.listeners.append(l)
