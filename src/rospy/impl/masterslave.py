"""rospy.impl.masterslave: ROSHandler, the slave API of this process's node (the calls other
nodes and the master make on it: getPid, getBusInfo, requestTopic, publisherUpdate, ...) called
as methods, answered by kame's Node as it answers them over XML-RPC.

rospy's ROSHandler is the node's implementation, made before the node registers; kame's node is
kame.node.Node, so this handler answers for the node init_node() started (ROSInitException
before it) whatever `name` and `master_uri` it is given. Answers are (code, status message,
value) as rospy's.
"""

from __future__ import annotations

from typing import Any

from kame.client import core
from kame.client.errors import ROSInitException

__all__ = ["ROSHandler"]


class ROSHandler:
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
