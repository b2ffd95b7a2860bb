"""rospy.impl.masterslave: ROSHandler, the slave API of this process's node (the calls other
nodes and the master make on it: getPid, getBusInfo, requestTopic, publisherUpdate, ...) called
as methods, answered by kame's Node as it answers them over XML-RPC.

rospy's ROSHandler is the node's implementation, made before the node registers; kame's node is
kame.node.Node, so this handler answers for the node init_node() started (ROSInitException
before it) whatever `name` and `master_uri` it is given. Answers are (code, status message,
value) as rospy's.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import Any

from kame.client import core
from kame.client.errors import ROSInitException
from rospy.core import *  # noqa: F403  (rospy.impl.masterslave re-exports rospy.core, as rospy's)
from rospy.core import __all__ as _core_names
from rospy.core import _lazy_names
from rospy.impl.paramserver import get_param_server_cache
from rospy.impl.registration import RegManager, get_topic_manager
from rospy.impl.validators import ParameterInvalid, non_empty

__all__ = [*_core_names, "LOG_API", "MSG", "STATUS", "VAL", "ROSHandler", "RegManager", "XmlRpcHandler",
           "apivalidate", "get_param_server_cache", "get_topic_manager", "is_publishers_list", "non_empty"]

# the places in an XML-RPC answer [code, status message, value]
STATUS = 0
MSG = 1
VAL = 2
LOG_API = True  # apivalidate logs each call and its answer at debug level

_logger = logging.getLogger("rospy.impl.masterslave")


def is_publishers_list(param_name: str) -> tuple[str, str]:
    """The validator, by name, of a list of publisher URIs (a handler's _custom_validate checks it)."""
    return ("is_publishers_list", param_name)


def apivalidate(error_return_value: Any, validators: Any = ()) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Decorate a slave or master API method (self, caller_id, *args): each argument after the
    caller ID goes through its validator (None: as it is; a (name, param) pair: the handler's
    _custom_validate), and a failure is answered as rospy does, with `error_return_value`:
    (-1, why) for a bad argument or caller ID, (0, "Internal failure: ...") for an exception."""
    def check_validates(f: Callable[..., Any]) -> Callable[..., Any]:
        argcount = f.__code__.co_argcount
        if len(validators) != argcount - 2:
            raise AssertionError(f"{f} failed arg check")

        def validated_f(*args: Any, **kwds: Any) -> Any:
            if LOG_API:
                _logger.debug("%s%s", f.__name__, args[1:])
            if len(args) == 1:
                _logger.error("%s invoked without caller_id parameter", f.__name__)
                return -1, "missing required caller_id parameter", error_return_value
            if len(args) != argcount:
                return -1, "Error: bad call arity", error_return_value
            instance, caller_id = args[0], args[1]
            if not isinstance(caller_id, str):
                _logger.error("%s: invalid caller_id param type", f.__name__)
                return -1, "caller_id must be a string", error_return_value
            new_args = [instance, caller_id]
            try:
                for validator, arg in zip(validators, args[2:], strict=True):
                    if not validator:
                        new_args.append(arg)
                        continue
                    try:
                        if isinstance(validator, (list, tuple)):
                            new_args.append(instance._custom_validate(validator[0], validator[1], arg, caller_id))
                        else:
                            new_args.append(validator(arg, caller_id))
                    except ParameterInvalid as exc:
                        _logger.error("%s: invalid parameter: %s", f.__name__, str(exc) or "error")
                        return -1, str(exc) or "error", error_return_value
                answer = f(*new_args, **kwds)
                if LOG_API:
                    _logger.debug("%s%s returns %s", f.__name__, args[1:], answer)
                    return answer
                code, msg, val = answer
                if val is None:
                    return -1, "Internal error (None value returned)", error_return_value
                return code, msg, val
            except TypeError as exc:
                _logger.exception("%s failed", f.__name__)
                return -1, f"Error: invalid arguments: {exc}", error_return_value
            except Exception as exc:
                _logger.exception("%s failed", f.__name__)
                return 0, f"Internal failure: {exc}", error_return_value

        validated_f.__name__ = f.__name__
        validated_f.__doc__ = f.__doc__
        return validated_f

    return check_validates


class XmlRpcHandler:
    """The interface of an XML-RPC node's handler (rosgraph.xmlrpc's): told when its server is
    ready at a URI and when it shuts down."""

    def _ready(self, uri: str) -> None:
        return None

    def _shutdown(self, reason: str) -> None:
        return None


class ROSHandler(XmlRpcHandler):
    """This process's node's slave API; each method takes the caller's ID first."""

    # the arguments (after the caller ID) of each method that are names: MasterProxy resolves them
    _remap_table: dict[str, list[int]] = {"requestTopic": [0]}

    @classmethod
    def remappings(cls, method_name: str) -> list[int]:
        return cls._remap_table.get(method_name, [])

    def __init__(self, name: str, master_uri: str) -> None:
        self.name = name
        self.master_uri = master_uri

    def _call(self, method: str, *params: Any) -> tuple[Any, ...]:
        node = core.get_node()
        if node is None:
            raise ROSInitException("the slave API is the node's: call init_node() first")
        answer = node.slave_call(method, list(params))
        if answer is None:  # every method here is one of the API's
            raise AssertionError(f"kame's node has no slave API method {method}")
        return tuple(answer)

    def getUri(self, caller_id: str) -> tuple[Any, ...]:
        return self._call("getUri", caller_id)

    def getName(self, caller_id: str) -> tuple[Any, ...]:
        return self._call("getName", caller_id)

    def getPid(self, caller_id: str) -> tuple[Any, ...]:
        return self._call("getPid", caller_id)

    def getMasterUri(self, caller_id: str) -> tuple[Any, ...]:
        return self._call("getMasterUri", caller_id)

    def getBusStats(self, caller_id: str) -> tuple[Any, ...]:
        return self._call("getBusStats", caller_id)

    def getBusInfo(self, caller_id: str) -> tuple[Any, ...]:
        return self._call("getBusInfo", caller_id)

    def getSubscriptions(self, caller_id: str) -> tuple[Any, ...]:
        return self._call("getSubscriptions", caller_id)

    def getPublications(self, caller_id: str) -> tuple[Any, ...]:
        return self._call("getPublications", caller_id)

    def requestTopic(self, caller_id: str, topic: str, protocols: list[Any]) -> tuple[Any, ...]:
        """[TCPROS, host, port] where `topic` is published, for the first protocol offered that we speak."""
        return self._call("requestTopic", caller_id, topic, protocols)

    def publisherUpdate(self, caller_id: str, topic: str, publishers: list[str]) -> tuple[Any, ...]:
        return self._call("publisherUpdate", caller_id, topic, publishers)

    def paramUpdate(self, caller_id: str, parameter_key: str, parameter_value: Any) -> tuple[Any, ...]:
        return self._call("paramUpdate", caller_id, parameter_key, parameter_value)

    def shutdown(self, caller_id: str, msg: str = "") -> tuple[Any, ...]:
        """Shut the node down, as a `rosnode kill` does."""
        return self._call("shutdown", caller_id, msg)


__getattr__ = _lazy_names(__name__)
