"""rospy.core: the process's node, shutdown and its hooks, logging, names and validators
(kame.client.core and kame.client.log underneath).

The shutdown hook lists are kame.client.core's own lists, and `_shutdown_flag` / `_in_shutdown`
read its state, so what rospy code appends or reads is what kame's shutdown runs and sets.
`md5` (hashlib, with OpenSSL) loads when first asked for: `import rospy` stays cheap.
"""

from __future__ import annotations

import logging
import os
import re
import threading
from collections.abc import Callable
from functools import partial, wraps
from typing import Any

from kame.client import core as _core
from kame.client.core import (
    add_client_shutdown_hook,
    add_preshutdown_hook,
    add_shutdown_hook,
    get_node,
    is_initialized,
    is_shutdown,
    is_shutdown_requested,
    set_initialized,
    signal_shutdown,
    wait_for_shutdown,
)
from kame.client.errors import ROSException
from rosgraph_msgs.msg import Log
from rospy._logging import *  # noqa: F403  (rospy.core is where rospy's log calls live)
from rospy._logging import __all__ as _logging_names
from rospy.names import *  # noqa: F403  (rospy.core re-exports rospy.names, as rospy's does)
from rospy.names import ParameterInvalid, get_mappings, valid_name_validator_resolved
from rospy.names import __all__ as _names_names

__all__ = [*_names_names, *_logging_names, "MASTER_NAME", "Log", "ROSRPC", "NullHandler", "add_client_shutdown_hook",
           "add_preshutdown_hook", "add_shutdown_hook", "configure_logging", "deprecated", "get_node",
           "get_node_uri", "get_ros_root", "is_initialized", "is_shutdown", "is_shutdown_requested", "is_topic",
           "on_shutdown", "parse_rosrpc_uri", "partial", "register_signals", "set_initialized", "set_node_uri",
           "signal_shutdown", "wait_for_shutdown", "xmlrpcapi"]

MASTER_NAME = "master"  # the master's reserved node name
ROSRPC = "rosrpc://"

# the lists kame's shutdown runs: appending here is adding a hook
_shutdown_hooks = _core._shutdown_hooks
_preshutdown_hooks = _core._preshutdown_hooks
_client_shutdown_hooks = _core._client_shutdown_hooks

_LAZY = {"md5": ("hashlib", "md5")}


def _lazy_names(module_name: str, lazy: dict[str, tuple[str, str]] | None = None) -> Callable[[str], Any]:
    """A module's __getattr__ that loads rospy.core's `md5` (and `lazy`'s names) when first asked
    for: the modules that re-export rospy.core use it too."""
    names = {**_LAZY, **(lazy or {})}

    def __getattr__(name: str) -> Any:
        if name not in names:
            raise AttributeError(f"module {module_name!r} has no attribute {name!r}")
        import importlib

        module, attribute = names[name]
        return getattr(importlib.import_module(module), attribute)

    return __getattr__


_lazy = _lazy_names(__name__)


def __getattr__(name: str) -> Any:
    if name == "_shutdown_flag":
        return _core.is_shutdown()
    if name == "_in_shutdown":
        return _core.is_shutdown_requested()
    return _lazy(name)


def on_shutdown(h: Callable[..., Any]) -> None:
    """Call `h()` when the node shuts down, before it begins its teardown (is_shutdown() is still
    false: it may publish); `h(reason)` if it takes the reason. At once if it already has."""
    add_client_shutdown_hook(h)


def deprecated(func: Callable[..., Any]) -> Callable[..., Any]:
    """`func`, warning with a DeprecationWarning each time it is called."""
    @wraps(func)
    def warned(*args: Any, **kwargs: Any) -> Any:
        import warnings

        warnings.warn(f"Call to deprecated function {func.__name__}.", category=DeprecationWarning, stacklevel=2)
        return func(*args, **kwargs)

    return warned


def parse_rosrpc_uri(uri: str) -> tuple[str, int]:
    """(address, port) of a `rosrpc://host:port` service URI; ParameterInvalid otherwise."""
    if not uri.startswith(ROSRPC):
        raise ParameterInvalid(f"Invalid protocol for ROS service URL: {uri}")
    dest_addr = uri[len(ROSRPC):]
    try:
        if "/" in dest_addr:
            dest_addr = dest_addr[:dest_addr.find("/")]
        dest_addr, dest_port = dest_addr.split(":")
        return dest_addr, int(dest_port)
    except ValueError:
        raise ParameterInvalid(f"ROS service URL is invalid: {uri}") from None


@deprecated
def get_ros_root(required: bool = False, env: dict[str, str] | None = None) -> str | None:
    """ROS_ROOT of `env` (default: the process's); ROSException when `required` and unset."""
    import rospkg

    ros_root = rospkg.get_ros_root(os.environ if env is None else env)
    if required and not ros_root:
        raise ROSException("ROS_ROOT is not set")
    return ros_root


_uri_override: tuple[object, str] | None = None  # (the node it was set for, the URI set_node_uri gave)


def get_node_uri() -> str | None:
    """The node's XML-RPC URI (None before init_node), or what set_node_uri said for this node."""
    node = get_node()
    if _uri_override is not None and _uri_override[0] is node:
        return _uri_override[1]
    return node.uri if node is not None else None


def set_node_uri(uri: str) -> None:
    """What get_node_uri answers for the present node; the node's XML-RPC server is unchanged (as rospy's)."""
    global _uri_override
    _uri_override = (get_node(), uri)


_log_filename: str | None = None


def configure_logging(node_name: str, level: int = logging.INFO) -> None:
    """Log `rospy`'s Python logging to a file in the ROS log folder named after `node_name`
    (or the command line's `__log:=`), as rosgraph.roslogging configures it."""
    global _log_filename
    from rosgraph import roslogging

    mappings = get_mappings()
    if "__log" in mappings:
        filename = os.path.abspath(mappings["__log"])
    else:
        suffix = ".log"
        filename = node_name.replace("/", "_") + suffix
        if filename[0] == "_":
            filename = filename[1:]
        if filename == suffix:
            raise ROSException(f"invalid configure_logging parameter: {node_name}")
    _log_filename = roslogging.configure_logging("rospy", level, filename=filename)


class NullHandler(logging.Handler):
    """A handler that drops every record."""

    def emit(self, record: logging.LogRecord) -> None:
        return None


def register_signals() -> None:
    """SIGINT and SIGTERM shut the node down (what init_node installs unless disable_signals)."""
    from kame.client import process

    process.install_signal_handlers()


def is_topic(param_name: str) -> Callable[[Any, str], str]:
    """A validator of a topic name parameter: a valid name, resolved, and not the root namespace."""
    def validator(param_value: Any, caller_id: str) -> str:
        resolved = valid_name_validator_resolved(param_name, param_value, caller_id)
        if param_value == "/":
            raise ParameterInvalid(f"ERROR: parameter [{param_name}] cannot be the global namespace")
        return resolved

    return validator


class _ServerProxy:
    """An XML-RPC server's methods as attributes, over kame's XML-RPC client (one kept-alive
    connection, its calls serialised): `xmlrpcapi(uri).getPid('/me')` -> [1, '', 4242]."""

    def __init__(self, uri: str) -> None:
        from kame.net.xmlrpc_client import XmlRpcProxy

        self._proxy = XmlRpcProxy(uri)

    def __getattr__(self, method: str) -> Callable[..., Any]:
        if method.startswith("__"):
            raise AttributeError(method)
        return partial(self._proxy.call, method)

    def __repr__(self) -> str:
        return f"<ServerProxy for {self._proxy.uri}>"


_URI = re.compile(r"[A-Za-z][A-Za-z0-9+.-]*://[^/?#]+")
_xmlrpc_cache: dict[str, _ServerProxy] = {}
_xmlrpc_lock = threading.Lock()


def xmlrpcapi(uri: str | None, cache: bool = True) -> _ServerProxy | None:
    """A proxy calling the XML-RPC server at `uri` (shared per URI when `cache`), or None
    when `uri` is not a URI with a scheme and a host."""
    if uri is None or not _URI.match(uri):
        return None
    if not cache:
        return _ServerProxy(uri)
    with _xmlrpc_lock:
        proxy = _xmlrpc_cache.get(uri)
        if proxy is None:
            proxy = _xmlrpc_cache[uri] = _ServerProxy(uri)
    return proxy


logging.getLogger("rospy").addHandler(NullHandler())  # as rospy's: quiet until configure_logging
