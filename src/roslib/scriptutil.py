"""roslib.scriptutil: the deprecated helpers of old scripts (rosgraph has their successors)."""

from __future__ import annotations

import functools
import os
import warnings
from collections.abc import Callable
from typing import Any, TypeVar

from rosgraph.xmlrpc import ServerProxy
from roslib import names as _names

__all__ = ["deprecated", "get_master", "get_param_server", "script_resolve_name"]

_F = TypeVar("_F", bound=Callable[..., Any])


def deprecated(func: _F) -> _F:
    """`func`, warning (DeprecationWarning) at each call."""
    @functools.wraps(func)
    def warned(*args: Any, **kwargs: Any) -> Any:
        warnings.warn(f"Call to deprecated function {func.__name__}.", category=DeprecationWarning, stacklevel=2)
        return func(*args, **kwargs)

    return warned  # type: ignore[return-value]


@deprecated
def script_resolve_name(script_name: str, name: str) -> str:
    """`name` resolved for a script (ROS_NAMESPACE; `~name` under the script's name; no remapping)."""
    if not name:
        return _names.get_ros_namespace()
    if _names.is_global(name):
        return name
    if _names.is_private(name):
        return _names.ns_join(_names.make_caller_id(script_name), name[1:])
    return _names.get_ros_namespace() + name


@deprecated
def get_master() -> ServerProxy:
    """An XML-RPC handle on the master at ROS_MASTER_URI (rosgraph.Master is the better one)."""
    return ServerProxy(os.environ["ROS_MASTER_URI"])


@deprecated
def get_param_server() -> ServerProxy:
    """The master's handle: it is the parameter server."""
    return ServerProxy(os.environ["ROS_MASTER_URI"])
