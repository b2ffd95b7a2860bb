"""rosgraph.masterapi: the master's XML-RPC API with its return codes checked.

Each call passes this handle's caller_id and returns the answer's value; code -1 raises
MasterError, code 0 MasterFailure (both MasterException), as rosgraph does. Each call is
`getattr(self.handle, method)(caller_id, ...)`, as rosgraph's, so code and tests may put their
own object in `handle`; the default handle is rosgraph.xmlrpc.ServerProxy, kame's XML-RPC
client; an unreachable master raises OSError (socket.error).
"""

from __future__ import annotations

from typing import Any

from .names import make_caller_id
from .network import parse_http_host_and_port
from .rosenv import get_master_uri
from .xmlrpc import ServerProxy

__all__ = ["Error", "Failure", "Master", "MasterError", "MasterException", "MasterFailure", "ROSMasterException",
           "ServerProxy", "is_online"]


class MasterException(Exception):
    """Base of the master's error answers."""


class MasterFailure(MasterException):
    """The master answered with code 0 (failure)."""


class MasterError(MasterException):
    """The master answered with code -1 (error)."""


Error = MasterError
Failure = MasterFailure
ROSMasterException = MasterException


def is_online(master_uri: str | None = None) -> bool:
    """True when a master answers at `master_uri` (default: the environment's)."""
    return Master("rosgraph", master_uri=master_uri).is_online()


class Master:
    """A handle on the master, calling as `caller_id` (resolved in ROS_NAMESPACE)."""

    def __init__(self, caller_id: str, master_uri: str | None = None) -> None:
        self._reinit(get_master_uri() if master_uri is None else master_uri)
        self.caller_id = make_caller_id(caller_id)
        if self.caller_id[-1] == "/":
            self.caller_id = self.caller_id[:-1]

    def _reinit(self, master_uri: str | None) -> None:
        if master_uri is None:
            raise ValueError("ROS master URI is not set")
        try:
            parse_http_host_and_port(master_uri)
        except ValueError:
            raise ValueError(f"invalid master URI: {master_uri}") from None
        self.master_uri = master_uri
        self.handle: Any = ServerProxy(master_uri)

    def is_online(self) -> bool:
        try:
            self.getPid()
        except Exception:  # any answer but a pid means no usable master, as in rosgraph
            return False
        return True

    def _succeed(self, args: Any) -> Any:
        code, msg, val = args
        if code == 1:
            return val
        if code == -1:
            raise MasterError(msg)
        raise MasterFailure(msg)

    def _call(self, method: str, *args: Any) -> Any:
        return self._succeed(getattr(self.handle, method)(self.caller_id, *args))

    # parameter server
    def deleteParam(self, key: str) -> Any:
        return self._call("deleteParam", key)

    def setParam(self, key: str, value: Any) -> Any:
        return self._call("setParam", key, value)

    def getParam(self, key: str) -> Any:
        return self._call("getParam", key)

    def searchParam(self, key: str) -> Any:
        return self._call("searchParam", key)

    def subscribeParam(self, caller_api: str, key: str) -> Any:
        return self._call("subscribeParam", caller_api, key)

    def unsubscribeParam(self, caller_api: str, key: str) -> Any:
        return self._call("unsubscribeParam", caller_api, key)

    def hasParam(self, key: str) -> Any:
        return self._call("hasParam", key)

    def getParamNames(self) -> Any:
        return self._call("getParamNames")

    # master
    def getPid(self) -> Any:
        return self._call("getPid")

    def getUri(self) -> Any:
        return self._call("getUri")

    def registerService(self, service: str, service_api: str, caller_api: str) -> Any:
        return self._call("registerService", service, service_api, caller_api)

    def lookupService(self, service: str) -> Any:
        return self._call("lookupService", service)

    def unregisterService(self, service: str, service_api: str) -> Any:
        return self._call("unregisterService", service, service_api)

    def registerSubscriber(self, topic: str, topic_type: str, caller_api: str) -> Any:
        return self._call("registerSubscriber", topic, topic_type, caller_api)

    def unregisterSubscriber(self, topic: str, caller_api: str) -> Any:
        return self._call("unregisterSubscriber", topic, caller_api)

    def registerPublisher(self, topic: str, topic_type: str, caller_api: str) -> Any:
        return self._call("registerPublisher", topic, topic_type, caller_api)

    def unregisterPublisher(self, topic: str, caller_api: str) -> Any:
        return self._call("unregisterPublisher", topic, caller_api)

    def lookupNode(self, node_name: str) -> Any:
        return self._call("lookupNode", node_name)

    def getPublishedTopics(self, subgraph: str) -> Any:
        return self._call("getPublishedTopics", subgraph)

    def getTopicTypes(self) -> Any:
        return self._call("getTopicTypes")

    def getSystemState(self) -> Any:
        return self._call("getSystemState")
