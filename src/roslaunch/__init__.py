"""roslaunch's Python API on kame: scriptapi.ROSLaunch, parent.ROSLaunchParent, rlutil, core
(Node, Test, Param, Machine, Master), config (ROSLaunchConfig, load_config_default), xmlloader.

`roslaunch.main()` is the command line (kame.cli.roslaunch).
"""

from __future__ import annotations

import sys
from collections.abc import Sequence

from roslaunch.core import Node, RLException
from roslaunch.parent import ROSLaunchParent
from roslaunch.scriptapi import ROSLaunch


def main(argv: Sequence[str] | None = None) -> None:
    from kame.cli.roslaunch import main as cli_main

    sys.exit(cli_main(list(sys.argv[1:] if argv is None else argv[1:])))


__all__ = ["Node", "RLException", "ROSLaunch", "ROSLaunchParent", "main"]
