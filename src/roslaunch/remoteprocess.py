"""roslaunch.remoteprocess: ssh_check_known_hosts (kame.net.ssh's check, in ROS's words) and
SSHChildROSLaunchProcess, which kame cannot provide (see its docstring)."""

from __future__ import annotations

import logging
import os
from typing import Any

from kame.net.server_proxy import ServerProxy
from kame.net.ssh import SSH_CONNECT_TIMEOUT, _user_config, known_hosts_problem
from roslaunch.core import printerrlog, printlog
from roslaunch.nodeprocess import DEFAULT_TIMEOUT_SIGINT, DEFAULT_TIMEOUT_SIGTERM
from roslaunch.server import ChildROSLaunchProcess

__all__ = ["DEFAULT_TIMEOUT_SIGINT", "DEFAULT_TIMEOUT_SIGTERM", "TIMEOUT_SSH_CONNECT", "SSHChildROSLaunchProcess",
           "ServerProxy", "printerrlog", "printlog", "ssh_check_known_hosts"]

TIMEOUT_SSH_CONNECT = float(SSH_CONNECT_TIMEOUT)

NO_XMLRPC_CHILD = (
    "kame's roslaunch runs the nodes of other machines through kame.launch.remote: one `roslaunch -c` "
    "per machine over SSH, sent its nodes as JSON on the SSH channel. It starts no child that registers "
    "back with the parent's XML-RPC server, which is what ROS's SSHChildROSLaunchProcess and "
    "ROSRemoteRunner drive; use roslaunch.parent.ROSLaunchParent, or run the nodes with <machine> tags.")


def ssh_check_known_hosts(ssh: Any, address: str, port: int, username: str | None = None,
                          logger: logging.Logger | None = None) -> str | None:
    """None when paramiko client `ssh` may connect to `address` (its ~/.ssh/config HostName), else what
    to do; ROSLAUNCH_SSH_UNKNOWN=1 accepts unknown hosts."""
    resolved = _user_config(address).get("hostname") or address
    return known_hosts_problem(ssh, resolved, port, username, os.environ)


class SSHChildROSLaunchProcess(ChildROSLaunchProcess):
    """Not available on kame: NotImplementedError (NO_XMLRPC_CHILD says why)."""

    def __init__(self, run_id: str, name: str, server_uri: str, machine: Any, master_uri: str | None = None,
                 sigint_timeout: float = DEFAULT_TIMEOUT_SIGINT,
                 sigterm_timeout: float = DEFAULT_TIMEOUT_SIGTERM) -> None:
        raise NotImplementedError(NO_XMLRPC_CHILD)
