"""roslaunch.remote: ROSRemoteRunner starts a roslaunch child per other machine over SSH
(roslaunch.remoteprocess), waits for each to register with the parent's server, then sends
each its nodes as launch XML.

Rules (roslaunch's remote, with its console wording):
- One child per machine configuration (machines alike but for their names share one), named
  `<address>-<N>`; one that cannot be started ends the launch.
- A child that dies before registering fails the launch (`remote roslaunch failed to launch`);
  one that does not register within its machine's timeout is listed as failed to register. A
  registration comes as an XML-RPC call (it sets the child's `registered` event); a child's death
  is seen only through is_alive(), so the wait looks at it every REMOTE_POLL_PERIOD.
- A child that does not answer `launch` has its nodes counted as failed.
"""

from __future__ import annotations

import logging
import time
from typing import Any

from kame.node.remote_poll import REMOTE_POLL_PERIOD
from roslaunch.core import Machine, Node, RLException, is_machine_local, printerrlog, printlog
from roslaunch.launch import ROSRemoteRunnerIF
from roslaunch.nodeprocess import DEFAULT_TIMEOUT_SIGINT, DEFAULT_TIMEOUT_SIGTERM
from roslaunch.remoteprocess import SSHChildROSLaunchProcess

__all__ = ["DEFAULT_TIMEOUT_SIGINT", "DEFAULT_TIMEOUT_SIGTERM", "RLException", "ROSRemoteRunner",
           "SSHChildROSLaunchProcess", "is_machine_local", "printerrlog", "printlog"]


class ROSRemoteRunner(ROSRemoteRunnerIF):
    """The children of the launch `rosconfig` on other machines, registered in `pm` and with `server`
    (a ROSLaunchParentNode)."""

    def __init__(self, run_id: str, rosconfig: Any, pm: Any, server: Any,
                 sigint_timeout: float = DEFAULT_TIMEOUT_SIGINT,
                 sigterm_timeout: float = DEFAULT_TIMEOUT_SIGTERM) -> None:
        self.run_id = run_id
        self.rosconfig = rosconfig
        self.server = server
        self.pm = pm
        self.sigint_timeout = sigint_timeout
        self.sigterm_timeout = sigterm_timeout
        self.logger = logging.getLogger("roslaunch.remote")
        self.listeners: list[Any] = []
        self.machine_list: list[Machine] = []
        self.remote_processes: list[SSHChildROSLaunchProcess] = []
        self.remote_nodes: dict[str, list[Node]] = {}

    def add_process_listener(self, l: Any) -> None:  # noqa: E741 (ROS's name)
        self.listeners.append(l)

    def _start_child(self, server_node_uri: str, machine: Machine, counter: int) -> SSHChildROSLaunchProcess:
        name = f"{machine.address}-{counter}"
        printlog(f"remote[{name}] starting roslaunch")
        p = SSHChildROSLaunchProcess(self.run_id, name, server_node_uri, machine, self.rosconfig.master.uri,
                                     sigint_timeout=self.sigint_timeout, sigterm_timeout=self.sigterm_timeout)
        success = p.start()
        self.pm.register(p)
        if not success:
            raise RLException(f"unable to start remote roslaunch child: {name}")
        self.server.add_child(name, p)
        return p

    def start_children(self) -> None:
        """Start a child per machine and wait for each to register."""
        server_node_uri = self.server.uri
        if not server_node_uri:
            raise RLException("server URI is not initialized")
        machines: dict[str, Machine] = {}
        for n in self.rosconfig.nodes:
            if not is_machine_local(n.machine):
                machines[n.machine.config_key()] = n.machine
        procs = [self._start_child(server_node_uri, m, counter) for counter, m in enumerate(machines.values())]
        start = time.monotonic()
        pending: list[Machine] = []
        for p in procs:
            while not p.registered.wait(REMOTE_POLL_PERIOD):
                if not p.is_alive():
                    raise RLException(f"remote roslaunch failed to launch: {p.machine.name}")
                if time.monotonic() > start + p.machine.timeout:
                    pending.append(p.machine)
                    break
        if pending:
            listed = "\n".join(f" * {m.name} (timeout {m.timeout}s)" for m in pending)
            raise RLException(f"The following roslaunch remote processes failed to register: \n{listed}\n\n"
                              "If this is a network latency issue, you may wish to consider setting \n"
                              '  <machine timeout="NUMBER OF SECONDS" ... />\nin your launch')
        self.machine_list = list(machines.values())
        self.remote_processes = procs

    def _assume_failed(self, nodes: list[Node], failed: list[str]) -> None:
        str_nodes = [f"{n.package}/{n.type}" for n in nodes]
        failed.extend(str_nodes)
        printerrlog(f"Launch of the following nodes most likely failed: {', '.join(str_nodes)}")

    def launch_remote_nodes(self) -> tuple[list[str], list[str]]:
        """Send each child its nodes: (succeeded, failed) as the children report them."""
        succeeded: list[str] = []
        failed: list[str] = []
        self.remote_nodes = {m.config_key(): [] for m in self.machine_list}
        for n in self.rosconfig.nodes:
            if not is_machine_local(n.machine):
                self.remote_nodes[n.machine.config_key()].append(n)
        for child in self.remote_processes:
            nodes = self.remote_nodes[child.machine.config_key()]
            body = "\n".join(n.to_remote_xml() for n in nodes)
            xml = f'<?xml version="1.0" encoding="utf-8"?>\n<launch>\n{body}</launch>'
            api = child.getapi()
            try:
                assert api is not None  # every child registered (start_children)
                reply: Any = api.launch(xml)
                code, msg, val = reply
            except OSError as exc:
                printerrlog(f"error launching on [{child.name}, uri {child.uri}]: {exc}")
                self._assume_failed(nodes, failed)
                continue
            if code == 1:
                succeeded.extend(val[0])
                failed.extend(val[1])
            else:
                printerrlog(f"error launching on [{child.name}, uri {child.uri}]: {msg}")
                self._assume_failed(nodes, failed)
        return succeeded, failed
