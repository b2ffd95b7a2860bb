"""roslaunch.arg_dump: `roslaunch --ros-args`: the <arg>s a launch file takes, over kame's loader."""

from __future__ import annotations

import os
import sys
from collections.abc import Sequence

from kame.cli.roslaunch import load_config
from kame.launch.errors import LaunchError
from roslaunch.config import load_config_default
from roslaunch.core import RLException

__all__ = ["RLException", "dump_args", "get_args", "load_config_default"]


def get_args(roslaunch_files: Sequence[str]) -> dict[str, tuple[str | None, str | None]]:
    """{name: (doc, default)} of the top-level file's <arg>s that are not fixed by a value."""
    try:
        _, loader = load_config(list(roslaunch_files), [], os.environ, resolve_anon=False, args_only=True)
    except LaunchError as exc:
        raise RLException(str(exc)) from None
    return {d.name: (d.doc, d.default) for d in loader.arg_decls}


def dump_args(roslaunch_files: Sequence[str]) -> None:
    """Print the required, then the optional arguments; exit status 1 on an error."""
    try:
        args = get_args(roslaunch_files)
    except RLException as exc:
        print(str(exc), file=sys.stderr)
        sys.exit(1)
    if not args:
        print("No arguments.")
        return
    required = sorted((n, doc or "undocumented") for n, (doc, default) in args.items() if not default)
    optional = sorted((n, doc or "undocumented", default) for n, (doc, default) in args.items() if default)
    if required:
        print("Required Arguments:")
        for name, doc in required:
            print(f"  {name}: {doc}")
    if optional:
        print("Optional Arguments:")
        for name, doc, default in optional:
            print(f'  {name} (default "{default}"): {doc}')
