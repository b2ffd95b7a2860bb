"""roslaunch.server: the XML-RPC server of a roslaunch, as roslaunch's API names it, on kame's
(kame.launch.server). A handler object answers the calls: each public method is an XML-RPC
method of that name (get_pid, list_processes, process_info, get_node_names; the parent's
register, list_children, process_died, log; the child's launch and shutdown), reading the
processes from a process monitor `pm` (roslaunch.pmon's ProcessMonitor, or any object with its
methods).

The child side is ROS's: ROSLaunchChildNode serves, registers with its parent's server, and its
handler's `launch(xml)` loads the XML sent and runs it with ROSLaunchRunner on the child's
process monitor; the child's printlog lines and its processes' deaths go to the parent (log,
process_died). kame's own roslaunch reaches other machines otherwise (kame.launch.remote: the
nodes as JSON over the SSH channel), so no port of the parent has to be reachable from them.
"""

from __future__ import annotations

import logging
import os
import threading
import traceback
from collections.abc import Callable
from typing import Any
from urllib.parse import urlparse

from kame.launch.server import RpcHandlerServer
from kame.launch.supervisor import say, say_bold, say_error
from kame.net.address import host_addresses
from kame.net.server_proxy import ServerProxy
from rosgraph.network import parse_http_host_and_port
from rosgraph_msgs.msg import Log
from roslaunch.core import (
    RLException,
    add_printerrlog_handler,
    add_printlog_handler,
    printerrlog,
    printlog,
    printlog_bold,
)
from roslaunch.launch import ROSLaunchRunner
from roslaunch.nodeprocess import DEFAULT_TIMEOUT_SIGINT, DEFAULT_TIMEOUT_SIGTERM
from roslaunch.pmon import Process, ProcessListener

__all__ = ["DEFAULT_TIMEOUT_SIGINT", "DEFAULT_TIMEOUT_SIGTERM", "ChildROSLaunchProcess", "Process", "ProcessListener",
           "ROSLaunchBaseHandler", "ROSLaunchChildHandler", "ROSLaunchChildNode", "ROSLaunchNode",
           "ROSLaunchParentHandler", "ROSLaunchParentNode", "ROSLaunchRunner", "ServerProxy", "add_printerrlog_handler",
           "add_printlog_handler", "printerrlog", "printlog", "printlog_bold", "urlparse"]

Answer = tuple[int, str, Any]


class ChildROSLaunchProcess(Process):
    """A roslaunch child on another machine, as the parent knows it: its URI once it registers
    (`registered` is set then)."""

    def __init__(self, name: str, args: list[Any], env: dict[str, str]) -> None:
        super().__init__("roslaunch", name, args, env, False)
        self.uri: str | None = None
        self.registered = threading.Event()

    def set_uri(self, uri: str) -> None:
        self.uri = uri
        self.registered.set()


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


class ROSLaunchChildHandler(ROSLaunchBaseHandler):
    """The child roslaunch's calls: launch (the XML its parent sends) and shutdown."""

    def __init__(self, run_id: str, name: str, server_uri: str, pm: Any, sigint_timeout: float = DEFAULT_TIMEOUT_SIGINT,
                 sigterm_timeout: float = DEFAULT_TIMEOUT_SIGTERM) -> None:
        super().__init__(pm)
        if server_uri is None:
            raise RLException("server_uri is not initialized")
        if parse_http_host_and_port(server_uri)[1] <= 0:
            raise RLException(f"ERROR: roslaunch server URI is not a valid XML-RPC URI. Value is [{server_uri}]")
        self.run_id = run_id
        self.name = name
        self.server_uri = server_uri
        self.sigint_timeout = sigint_timeout
        self.sigterm_timeout = sigterm_timeout
        self.server = ServerProxy(server_uri)

    def _shutdown(self, reason: str) -> Answer:
        if self.pm is not None:
            self.pm.shutdown()
            self.pm.join()
            self.pm = None
        return 1, "", 1

    def shutdown(self) -> Answer:
        """Stop the child's processes."""
        self._shutdown("external call")
        return 1, "success", 1

    def _log(self, level: int, message: str) -> None:
        self.logger.debug(message)
        try:
            self.server.log(str(self.name), level, str(message))
        except Exception:  # the parent gone: the child's own log still has it
            self.logger.error(traceback.format_exc())

    def launch(self, launch_xml: str) -> Answer:
        """Run the nodes of `launch_xml` (parameters and master are the parent's): [succeeded, failed]."""
        from roslaunch.config import ROSLaunchConfig
        from roslaunch.xmlloader import XmlLoader, XmlParseException

        if self.pm is None:
            return 0, "uninitialized", -1
        rosconfig = ROSLaunchConfig()
        try:
            XmlLoader().load_string(launch_xml, rosconfig)
        except XmlParseException as exc:
            return -1, f"ERROR: {exc}", [[], []]
        rosconfig.assign_machines()
        try:
            self._log(Log.INFO, "launching nodes...")
            runner = ROSLaunchRunner(self.run_id, rosconfig, server_uri=self.server_uri, pmon=self.pm, is_child=True,
                                     sigint_timeout=self.sigint_timeout, sigterm_timeout=self.sigterm_timeout)
            succeeded, failed = runner.launch()
            self._log(Log.INFO, "... done launching nodes")
            self.pm.registrations_complete()
            return 1, "launched", [succeeded, failed]
        except Exception:  # as ROS: the parent is told what went wrong
            return 0, f"ERROR: {traceback.format_exc()}", [[], []]


class _ProcessListenerForwarder(ProcessListener):
    """The child's process deaths, told to the parent."""

    def __init__(self, server: ServerProxy) -> None:
        self.server = server

    def process_died(self, process_name: str, exit_code: int | None) -> None:
        try:
            self.server.process_died(process_name, exit_code if exit_code is not None else -1)
        except Exception:
            logging.getLogger("roslaunch.server").error(traceback.format_exc())


class ROSLaunchChildNode(ROSLaunchNode):
    """A child roslaunch's server: it registers with its parent's at `server_uri` once started."""

    def __init__(self, run_id: str, name: str, server_uri: str, pm: Any, sigint_timeout: float = DEFAULT_TIMEOUT_SIGINT,
                 sigterm_timeout: float = DEFAULT_TIMEOUT_SIGTERM) -> None:
        self.logger = logging.getLogger("roslaunch.server")
        self.run_id = run_id
        self.name = name
        self.server_uri = server_uri
        self.pm = pm
        if self.pm is None:
            raise RLException("cannot create child node: pm is not initialized")
        super().__init__(ROSLaunchChildHandler(run_id, name, server_uri, pm, sigint_timeout=sigint_timeout,
                                               sigterm_timeout=sigterm_timeout))

    def _register_with_server(self) -> None:
        name = self.name
        server = ServerProxy(self.server_uri)
        try:
            reply: Any = server.register(name, self.uri)
            code, msg, _ = reply
        except Exception as exc:
            raise RLException(f"Exception while registering with roslaunch parent [{self.server_uri}]: "
                              f"{traceback.format_exc()}") from exc
        if code != 1:
            raise RLException(f"unable to register with roslaunch server: {msg}")
        add_printlog_handler(lambda msg: server.log(name, Log.INFO, msg))
        add_printerrlog_handler(lambda msg: server.log(name, Log.ERROR, msg))
        self.pm.add_process_listener(_ProcessListenerForwarder(server))

    def start(self) -> None:
        """Serve, then register with the parent."""
        super().start()
        self._register_with_server()
