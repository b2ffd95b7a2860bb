"""rospy.service: Service, ServiceProxy, wait_for_service (kame.client.services), and rospy's
registry of services: ServiceManager and _Service, the base of a service's description.

The process's ServiceManager (set as the service manager when this module loads, as rospy's) holds
what rospy code registers with it and answers for the services kame's node serves too (Service
registers with the node, which tells the registration listeners, as rospy's
ServiceManager.register does).
"""

from __future__ import annotations

import logging
import threading
from abc import ABCMeta
from typing import Any

from kame.client import core as _client_core
from kame.client.services import (
    Service,
    ServiceException,
    ServiceImpl,
    ServiceProxy,
    wait_for_service,
)
from rospy.core import *  # noqa: F403  (rospy.service re-exports rospy.core, as rospy's)
from rospy.core import __all__ as _core_names
from rospy.core import _lazy_names, resolve_name
from rospy.impl.registration import Registration, get_registration_listeners, set_service_manager
from rospy.impl.transport import *  # noqa: F403
from rospy.impl.transport import __all__ as _transport_names

__all__ = [*_core_names, *_transport_names, "Registration", "Service", "ServiceException", "ServiceManager",
           "ServiceProxy", "get_registration_listeners", "logger", "set_service_manager", "wait_for_service"]

logger = logging.getLogger("rospy.service")


class _Service(metaclass=ABCMeta):  # noqa: B024  (an ABC for its register(), with nothing abstract)
    """A service's resolved name, class, request and response classes and URI (kame's Service is
    one: registered below)."""

    def __init__(self, name: str, service_class: Any) -> None:
        self.resolved_name = resolve_name(name)
        self.service_class = service_class
        self.request_class = service_class._request_class
        self.response_class = service_class._response_class
        self.uri: str | None = None


class ServiceManager:
    """The services of this process by resolved name; registrations and removals are told to
    `registration_listeners` (the process's by default)."""

    def __init__(self, registration_listeners: Any = None) -> None:
        self.map: dict[str, Any] = {}
        self.lock = threading.RLock()
        self.registration_listeners = registration_listeners or get_registration_listeners()

    @staticmethod
    def _node_services() -> dict[str, str]:
        node = _client_core.get_node()
        if node is None:
            return {}
        return {name: node.service_uri for name in list(node.services)}

    def get_services(self) -> list[tuple[str, Any]]:
        """(resolved name, service URI) of each service."""
        with self.lock:
            registered = [(name, service.uri) for name, service in self.map.items()]
        return registered + [(name, uri) for name, uri in self._node_services().items() if name not in self.map]

    def unregister_all(self) -> None:
        self.map.clear()

    def register(self, resolved_service_name: str, service: Any) -> None:
        """Hold `service` as `resolved_service_name` and tell the listeners; ServiceException if
        the name is taken (the listeners are told all the same, as rospy's)."""
        err = None
        with self.lock:
            if resolved_service_name in self.map or resolved_service_name in self._node_services():
                err = f"service [{resolved_service_name}] already registered"
            else:
                self.map[resolved_service_name] = service
            self.registration_listeners.notify_added(resolved_service_name, service.uri, Registration.SRV)
        if err:
            raise ServiceException(err)

    def unregister(self, resolved_service_name: str, service: Any) -> None:
        with self.lock:
            if self.map.get(resolved_service_name) == service:
                del self.map[resolved_service_name]
            self.registration_listeners.notify_removed(resolved_service_name, service.uri, Registration.SRV)

    def get_service(self, resolved_service_name: str) -> Any:
        """The service held as `resolved_service_name` (the node's server for one kame serves), or None."""
        found = self.map.get(resolved_service_name)
        if found is None:
            node = _client_core.get_node()
            found = node.services.get(resolved_service_name) if node is not None else None
        return found


_Service.register(ServiceImpl)
set_service_manager(ServiceManager())
__getattr__ = _lazy_names(__name__)
