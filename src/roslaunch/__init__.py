"""roslaunch's Python API on kame: scriptapi.ROSLaunch, parent.ROSLaunchParent, rlutil, core
(Node, Test, Param, Machine, Master), config (ROSLaunchConfig, load_config_default), xmlloader.

`roslaunch.main()` is the command line (kame.cli.roslaunch).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Sequence

from roslaunch.core import Node, RLException
from roslaunch.parent import ROSLaunchParent
from roslaunch.scriptapi import ROSLaunch


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


def main(argv: Sequence[str] | None = None) -> None:
    from kame.cli.roslaunch import main as cli_main

    sys.exit(cli_main(list(sys.argv[1:] if argv is None else argv[1:])))


__all__ = ["Node", "RLException", "ROSLaunch", "ROSLaunchParent", "configure_logging", "main"]
