"""roslaunch.remote: ROSRemoteRunner, which kame cannot provide: kame's roslaunch reaches other
machines through kame.launch.remote instead (roslaunch.remoteprocess.NO_XMLRPC_CHILD says why)."""

from __future__ import annotations

from typing import Any

from roslaunch.core import RLException, is_machine_local, printerrlog, printlog
from roslaunch.launch import ROSRemoteRunnerIF
from roslaunch.nodeprocess import DEFAULT_TIMEOUT_SIGINT, DEFAULT_TIMEOUT_SIGTERM
from roslaunch.remoteprocess import NO_XMLRPC_CHILD, SSHChildROSLaunchProcess

__all__ = ["DEFAULT_TIMEOUT_SIGINT", "DEFAULT_TIMEOUT_SIGTERM", "RLException", "ROSRemoteRunner",
           "SSHChildROSLaunchProcess", "is_machine_local", "printerrlog", "printlog"]


class ROSRemoteRunner(ROSRemoteRunnerIF):
    """Not available on kame: NotImplementedError (NO_XMLRPC_CHILD says why)."""

    def __init__(self, run_id: str, rosconfig: Any, pm: Any, server: Any,
                 sigint_timeout: float = DEFAULT_TIMEOUT_SIGINT,
                 sigterm_timeout: float = DEFAULT_TIMEOUT_SIGTERM) -> None:
        raise NotImplementedError(NO_XMLRPC_CHILD)
