"""rospy.client: init_node, spin, parameters and the other top-level functions (kame.client.process)."""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping
from threading import Lock
from typing import Any

from kame import environ as _environ
from kame import names as _names
from kame.client import core as _core
from kame.client import log as _log
from kame.client.errors import ROSInitException
from kame.client.process import (
    DEFAULT_MASTER_URI,
    delete_param,
    get_param,
    get_param_cached,
    get_param_names,
    get_published_topics,
    has_param,
    init_node,
    myargv,
    search_param,
    set_param,
    spin,
    wait_for_message,
)
from kame.client.services import Service
from roscpp.msg import Logger
from roscpp.srv import GetLoggers, GetLoggersResponse, SetLoggerLevel, SetLoggerLevelResponse
from rosgraph_msgs.msg import Log
from rospy._logging import logdebug, logerr, loginfo, logwarn
from rospy.core import _lazy_names, on_shutdown
from rospy.impl import init as _init  # noqa: F401  (rospy.client loads these, as rospy's)
from rospy.impl import rosout as _rosout  # noqa: F401
from rospy.impl import simtime as _simtime  # noqa: F401

__all__ = [
    "DEBUG",
    "DEFAULT_MASTER_URI",
    "ERROR",
    "FATAL",
    "INFO",
    "TIMEOUT_READY",
    "WARN",
    "GetLoggers",
    "GetLoggersResponse",
    "Lock",
    "Log",
    "Logger",
    "Service",
    "SetLoggerLevel",
    "SetLoggerLevelResponse",
    "delete_param",
    "get_master",
    "get_param",
    "get_param_cached",
    "get_param_names",
    "get_published_topics",
    "has_param",
    "init_node",
    "load_command_line_node_params",
    "logdebug",
    "logerr",
    "loginfo",
    "logwarn",
    "myargv",
    "on_shutdown",
    "search_param",
    "set_param",
    "spin",
    "wait_for_message",
]

TIMEOUT_READY = 15.0  # rospy's wait, in seconds, for a node to be ready
DEBUG = _log.DEBUG
INFO = _log.INFO
WARN = _log.WARN
ERROR = _log.ERROR
FATAL = _log.FATAL

__getattr__ = _lazy_names(__name__)

_master_proxy: Any = None
_master_proxy_lock = Lock()


def get_master(env: Mapping[str, str] = os.environ) -> Any:
    """The master as a rospy.msproxy.MasterProxy (this node's, else `env`'s ROS_MASTER_URI or the
    command line's `__master:=`), made once per process."""
    global _master_proxy
    from rospy.msproxy import MasterProxy

    with _master_proxy_lock:
        if _master_proxy is None:
            node = _core.get_node()
            uri = node.config.master_uri if node is not None else _environ.master_uri(
                env, _names.parse_args(sys.argv).special)
            _master_proxy = MasterProxy(uri)
    return _master_proxy


def load_command_line_node_params(argv: list[str]) -> dict[str, Any]:
    """The private parameters of a command line (`_rate:=10` -> {'rate': 10}, values read as YAML)."""
    from kame import param_yaml  # here: PyYAML is 2.5 MB that a node without such parameters never needs

    try:
        params = _names.parse_args(argv).params
        return {key[len(_names.PRIVATE_PREFIX):]: param_yaml.safe_load(text) for key, text in params.items()
                if key != _names.PRIVATE_PREFIX}  # `_:=x` names no parameter
    except Exception as exc:
        raise ROSInitException(f"invalid command-line parameters: {exc}") from exc
