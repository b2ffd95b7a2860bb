"""roslaunch.substitution_args: resolve_args over kame's substituter (kame.launch.substitution):
$(find), $(arg), $(env), $(optenv), $(anon), $(dirname) and $(eval).

`context` is ROS's dictionary: its `arg` entry holds the args, its `anon` entry the anonymous
names made so far (filled in, so later calls with the same context give the same names), its
`filename` entry the file $(dirname) names. Errors are ROS's: SubstitutionException, ArgException
(the name of an arg with no value), rospkg.ResourceNotFound for an unknown package.
"""

from __future__ import annotations

import os
from io import StringIO
from typing import Any

from kame.cli.roslaunch import anonymous_name, loader_host
from kame.launch.errors import ArgError, LaunchError, PackageNotFound
from kame.launch.substitution import Substituter
from roslaunch.loader import convert_value
from rospkg import ResourceNotFound

__all__ = ["ArgException", "StringIO", "SubstitutionException", "convert_value", "resolve_args"]


class SubstitutionException(Exception):
    """A substitution arg that cannot be resolved."""


class ArgException(SubstitutionException):
    """$(arg name) of an arg with no value: the message is the name."""


def resolve_args(arg_str: str | None, context: dict[str, Any] | None = None, resolve_anon: bool = True,
                 filename: str | None = None) -> str | None:
    """`arg_str` with its substitution args resolved (None and "" as given)."""
    if context is None:
        context = {}
    if not arg_str:
        return arg_str
    # resolve_anon is taken and, as by ROS's resolve_args (1.15), not acted on: $(anon) is always resolved
    substituter = Substituter(os.environ, loader_host(os.environ).find_package, anonymous_name)
    substituter.anons = context.setdefault("anon", {})
    args = context.setdefault("arg", {})
    try:
        return substituter.resolve(arg_str, args, context.get("filename", filename))
    except ArgError as exc:
        raise ArgException(str(exc)) from None
    except PackageNotFound as exc:
        raise ResourceNotFound(str(exc)) from None
    except LaunchError as exc:
        raise SubstitutionException(str(exc)) from None
