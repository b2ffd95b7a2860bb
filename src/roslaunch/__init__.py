"""roslaunch's Python API on kame, module for module as ROS's: scriptapi.ROSLaunch, parent.ROSLaunchParent,
core, config, loader, xmlloader, substitution_args, pmon, nodeprocess, launch, server, child, node_args,
param_dump, arg_dump, depends, netapi, rlutil, roslaunch_logs, remote and remoteprocess.

`roslaunch.main()` is the command line (kame.cli.roslaunch).
"""

from __future__ import annotations

import os
import sys
import traceback
from collections.abc import Sequence
from logging import Logger
from types import ModuleType

import rospkg
from roslaunch import core as roslaunch_core
from roslaunch import param_dump as roslaunch_param_dump
from roslaunch.config import ROSLaunchConfig
from roslaunch.core import Master, Node, RLException, Test
from roslaunch.launch import ROSLaunchRunner
from roslaunch.nodeprocess import DEFAULT_TIMEOUT_SIGINT, DEFAULT_TIMEOUT_SIGTERM
from roslaunch.parent import ROSLaunchParent
from roslaunch.pmon import Process
from roslaunch.scriptapi import ROSLaunch
from roslaunch.xmlloader import XmlLoader, XmlParseException
from rosmaster import DEFAULT_MASTER_PORT, NUM_WORKERS

NAME = "roslaunch"

__all__ = ["DEFAULT_MASTER_PORT", "DEFAULT_TIMEOUT_SIGINT", "DEFAULT_TIMEOUT_SIGTERM", "NAME", "NUM_WORKERS", "Master",
           "Node", "Process", "RLException", "ROSLaunch", "ROSLaunchConfig", "ROSLaunchParent", "ROSLaunchRunner",
           "Test", "XmlLoader", "XmlParseException", "configure_logging", "handle_exception", "main",
           "roslaunch_core", "roslaunch_param_dump", "write_pid_file"]


def configure_logging(uuid: str) -> None:
    """Log roslaunch's records to `<ROS_HOME>/log/<uuid>/roslaunch-<host>-<pid>.log`, as scripts
    using roslaunch call it first (ROS's scripted-launch recipe); says where, or why not."""
    from kame.cli.roslaunch import LOGGER
    from kame.cli.rosmaster import setup_file_logging
    from kame.launch.runner import run_dir_of
    from kame.net import interfaces

    try:
        path = run_dir_of(os.environ, uuid) / f"roslaunch-{interfaces.hostname()}-{os.getpid()}.log"
        setup_file_logging(path, LOGGER)
    except OSError:
        print("WARNING: unable to configure logging. No log files will be generated", file=sys.stderr)
        return
    print(f"... logging to {path}")


def write_pid_file(options_pid_fn: str | None, options_core: bool, port: int | None) -> None:
    """Write our PID to `options_pid_fn`, or for a core to `<ROS_HOME>/roscore-<port>.pid`."""
    if not (options_pid_fn or options_core):
        return
    ros_home = rospkg.get_ros_home()
    if options_pid_fn:
        pid_fn = os.path.expanduser(options_pid_fn)
        if os.path.dirname(pid_fn) == ros_home:
            os.makedirs(ros_home, exist_ok=True)
    else:
        pid_fn = os.path.join(ros_home, f"roscore-{port or DEFAULT_MASTER_PORT}.pid")
        os.makedirs(ros_home, exist_ok=True)
    with open(pid_fn, "w") as f:
        f.write(str(os.getpid()))


def handle_exception(roslaunch_core: ModuleType, logger: Logger | None, msg: str, e: BaseException) -> None:
    """Print `msg` and the error in red, log the traceback, and exit with status 1."""
    roslaunch_core.printerrlog(msg + str(e))
    roslaunch_core.printerrlog("The traceback for the exception was written to the log file")
    if logger:
        logger.error(traceback.format_exc())
    sys.exit(1)


def main(argv: Sequence[str] | None = None) -> None:
    from kame.cli.roslaunch import main as cli_main

    sys.exit(cli_main(list(sys.argv[1:] if argv is None else argv[1:])))


# the modules a ROS program reaches through `import roslaunch` (roslaunch.parent.ROSLaunchParent, ...)
from roslaunch import (  # noqa: E402, F401
    arg_dump,
    child,
    depends,
    netapi,
    node_args,
    remote,
    remoteprocess,
    rlutil,
    roslaunch_logs,
    server,
    substitution_args,
)
