"""rospy.logger_level_service_caller: a node's loggers and their levels, read and set through its
~get_loggers and ~set_logger_level services (what rqt_logger_level and rosconsole call), over
kame's rosnode and rosservice modules and ServiceProxy."""

from __future__ import annotations

from typing import Any

from kame.client.services import ServiceException, ServiceProxy
from rospy.names import _rosgraph_resolve as _resolve_name
from rospy.names import get_ros_namespace, ns_join

__all__ = ["LoggerLevelServiceCaller", "ROSConsoleException"]


class ROSConsoleException(Exception):
    """A node's logger services could not be reached or answered wrongly."""


def _service_name(node: str, service: str) -> str:
    return _resolve_name(ns_join(ns_join(get_ros_namespace(), node), service), get_ros_namespace())


class LoggerLevelServiceCaller:
    """Lists the nodes that serve set_logger_level, a node's loggers and levels, and changes them."""

    def __init__(self) -> None:
        self._current_loggers: list[str] = []
        self._current_levels: dict[str, str] = {}

    def get_levels(self) -> list[str]:
        return ["debug", "info", "warn", "error", "fatal"]

    def get_loggers(self, node: str) -> list[str]:
        """`node`'s logger names (its levels kept for send_logger_change_message); ROSConsoleException
        when it cannot be asked."""
        self._refresh_loggers(node)
        return self._current_loggers

    def get_node_names(self) -> list[str]:
        """The nodes that serve ~set_logger_level, sorted."""
        import rosnode
        import rosservice

        return [name for name in sorted(rosnode.get_node_names())
                if name + "/set_logger_level" in rosservice.get_service_list(name)]

    def _refresh_loggers(self, node: str) -> None:
        import rosservice

        self._current_loggers = []
        self._current_levels = {}
        servicename = _service_name(node, "get_loggers")
        try:
            service = rosservice.get_service_class_by_name(servicename)
        except rosservice.ROSServiceException as exc:
            raise ROSConsoleException(f"node '{node}' doesn't exist or doesn't support query: {exc}") from exc
        try:
            response = ServiceProxy(str(servicename), service)(service._request_class())
        except ServiceException as exc:
            raise ROSConsoleException(f"node '{node}' logger request failed: {exc}") from exc
        if response._slot_types[0] != "roscpp/Logger[]":
            raise ROSConsoleException(repr(response))
        for logger in getattr(response, response.__slots__[0]):
            self._current_loggers.append(logger.name)
            self._current_levels[logger.name] = logger.level

    def send_logger_change_message(self, node: str, logger: str, level: str) -> bool:
        """Set `node`'s `logger` to `level`; False when it already is at that level (as last read)."""
        import rosservice

        servicename = _service_name(node, "set_logger_level")
        if self._current_levels[logger] == level:
            return False
        service: Any = rosservice.get_service_class_by_name(servicename)
        request = service._request_class()
        request.logger = logger
        request.level = level
        try:
            ServiceProxy(str(servicename), service)(request)
        except ServiceException as exc:
            raise ROSConsoleException(f"node '{node}' logger request failed: {exc}") from exc
        self._current_levels[logger] = level.upper()
        return True
