"""roslaunch.remoteprocess: SSHChildROSLaunchProcess, a roslaunch child started over SSH that
registers back with the parent's XML-RPC server (ROS's protocol), and ssh_check_known_hosts.

Rules (roslaunch's remoteprocess, with its console wording), over kame's SSH (kame.net.ssh:
~/.ssh/config, known_hosts, keys or password, ROSLAUNCH_SSH_UNKNOWN=1):
- The child is `env ROS_MASTER_URI=<uri> <env-loader> roslaunch -c <name> -u <server uri>
  --run_id <id> --sigint-timeout S --sigterm-timeout T` on the machine: ROS's roslaunch there.
  kame's own `roslaunch -c` takes its nodes on the SSH channel instead (kame.launch.remote) and
  does not register, so the parent reports it as not registered.
- Its stderr lines are printed red as `remote[<name>]: <line>`, its stdout lines as they come.
- It is alive until both its streams end. Stopping asks it to shut down over XML-RPC, closes its
  stdin and the connection.
"""

from __future__ import annotations

import logging
import os
import threading
from collections.abc import Callable
from typing import Any

from kame.net.server_proxy import ServerProxy
from kame.net.ssh import SSH_CONNECT_TIMEOUT, RemoteCommand, SshError, SshTarget, _user_config, known_hosts_problem
from roslaunch.core import printerrlog, printlog
from roslaunch.nodeprocess import DEFAULT_TIMEOUT_SIGINT, DEFAULT_TIMEOUT_SIGTERM
from roslaunch.server import ChildROSLaunchProcess

__all__ = ["DEFAULT_TIMEOUT_SIGINT", "DEFAULT_TIMEOUT_SIGTERM", "TIMEOUT_SSH_CONNECT", "SSHChildROSLaunchProcess",
           "ServerProxy", "printerrlog", "printlog", "ssh_check_known_hosts"]

_logger = logging.getLogger("roslaunch.remoteprocess")
TIMEOUT_SSH_CONNECT = float(SSH_CONNECT_TIMEOUT)
STOP_GRACE = 5.0  # beyond the child's own SIGINT + SIGTERM timeouts, for its exit to reach us


def ssh_check_known_hosts(ssh: Any, address: str, port: int, username: str | None = None,
                          logger: logging.Logger | None = None) -> str | None:
    """None when paramiko client `ssh` may connect to `address` (its ~/.ssh/config HostName), else what
    to do; ROSLAUNCH_SSH_UNKNOWN=1 accepts unknown hosts."""
    resolved = _user_config(address).get("hostname") or address
    return known_hosts_problem(ssh, resolved, port, username, os.environ)


class SSHChildROSLaunchProcess(ChildROSLaunchProcess):
    """The roslaunch child on `machine` (whose env_loader must be set), for the parent at `server_uri`."""

    # what runs the command on the machine: kame's SSH connection (a test runs it here instead)
    transport: Callable[..., Any] = RemoteCommand

    def __init__(self, run_id: str, name: str, server_uri: str, machine: Any, master_uri: str | None = None,
                 sigint_timeout: float = DEFAULT_TIMEOUT_SIGINT,
                 sigterm_timeout: float = DEFAULT_TIMEOUT_SIGTERM) -> None:
        if not machine.env_loader:
            raise ValueError("machine.env_loader must have been assigned before creating ssh child instance")
        args = [machine.env_loader, "roslaunch", "-c", name, "-u", server_uri, "--run_id", run_id,
                "--sigint-timeout", str(sigint_timeout), "--sigterm-timeout", str(sigterm_timeout)]
        super().__init__(name, args, {})
        self.machine = machine
        self.master_uri = master_uri
        self.sigint_timeout = sigint_timeout
        self.sigterm_timeout = sigterm_timeout
        self.command: Any = None
        self.started = False
        self.is_dead = False
        self.ended = threading.Event()

    def _stdout(self, line: str) -> None:
        printlog(line)

    def _stderr(self, line: str) -> None:
        printerrlog(f"remote[{self.name}]: {line}")

    def _end(self) -> None:
        self.is_dead = True
        self.ended.set()

    def start(self) -> bool:
        """Connect and start the child: False (said why) when it cannot be."""
        self.started = False
        self.command = None
        self.ended.clear()
        assert self.lock is not None
        with self.lock:
            m = self.machine
            user = f", user[{m.user}]" if m.user is not None else ""
            printlog(f"remote[{self.name}]: creating ssh connection to {m.address}:{m.ssh_port}{user}")
            command = " ".join(self.args)
            if self.master_uri:
                command = f"env ROS_MASTER_URI={self.master_uri} {command}"
            try:
                self.command = self.transport(SshTarget(m.address, m.ssh_port, m.user, m.password), command,
                                              self._stdout, self._stderr, self._end)
            except SshError as exc:
                printerrlog(f"remote[{self.name}]: failed to launch on {m.name}:\n\n{exc}\n\n")
                return False
            printlog(f"launching remote roslaunch child with command: [{command}]")
            printlog(f"remote[{self.name}]: ssh connection created")
            self.started = True
            return True

    def getapi(self) -> ServerProxy | None:
        """The child's XML-RPC server, once it registered."""
        return ServerProxy(self.uri) if self.uri else None

    def is_alive(self) -> bool:
        if not self.started:
            return True  # not started counts as alive, as in ROS
        return self.command is not None and not self.is_dead

    def stop(self, errors: list[str] | None = None) -> None:
        """Ask the child to shut down, then close its input and the connection."""
        assert self.lock is not None
        with self.lock:
            command, self.command = self.command, None
            if command is None:
                return
            try:
                api = self.getapi()
                if api is not None:
                    api.shutdown()
            except OSError:
                address = self.machine.address
                if not self.is_dead:
                    printerrlog(f"remote[{self.name}]: unable to contact [{address}] to shutdown remote processes!")
                else:
                    printlog(f"remote[{self.name}]: unable to contact [{address}] to shutdown cleanly. The remote "
                             "roslaunch may have exited already.")
            command.close_stdin()
            command.wait(self.sigint_timeout + self.sigterm_timeout + STOP_GRACE)
            command.close()
