"""Service, ServiceProxy, wait_for_service and ServiceException (rospy's) over kame's Node."""

from __future__ import annotations

import io
import os
import time
import traceback
from collections.abc import Callable
from typing import Any

from kame import environ
from kame.client import core
from kame.client import log as _log
from kame.client.errors import ROSException, ROSInitException, ROSInterruptException, ROSSerializationException
from kame.client.message_args import args_kwds_to_message
from kame.msg.errors import SerializationError
from kame.node.master_proxy import MasterError, MasterProxy
from kame.node.services import ServiceClient, ServiceError, probe_service


class ServiceException(ROSException):
    """A service call failed (raised by handlers to report an error, and by proxies)."""


def _node() -> Any:
    node = core.get_node()
    if node is None:
        raise ROSInitException("client code must call rospy.init_node() first")
    return node


_anonymous_master: MasterProxy | None = None


def _master_and_caller() -> tuple[MasterProxy, str]:
    """The node's master and name, or, before init_node (allowed for service clients, as in
    rospy), a master from ROS_MASTER_URI and the caller id /unnamed."""
    global _anonymous_master
    node = core.get_node()
    if node is not None:
        return node.master, node.name
    if _anonymous_master is None:
        _anonymous_master = MasterProxy(environ.master_uri(os.environ), core.get_caller_id())
    return _anonymous_master, core.get_caller_id()


def _serialize(msg: Any) -> bytes:
    buff = io.BytesIO()
    msg.serialize(buff)
    return buff.getvalue()


def _to_response(value: Any, response_class: type[Any]) -> Any:
    """rospy's conversion of what a handler returned into the response message."""
    if isinstance(value, response_class):
        return value
    if isinstance(value, dict):
        return response_class(**value)
    if isinstance(value, (list, tuple)):
        return response_class(*value)
    if len(response_class.__slots__) == 1:
        return response_class(value)
    raise ServiceException(f"handler returned wrong type: expected [{response_class._type}], got {type(value)}")


class ServiceImpl:
    def __init__(self, name: str, service_class: type[Any], handler: Callable[[Any], Any],
                 buff_size: int = 65536, error_handler: Callable[..., Any] | None = None) -> None:
        self.resolved_name = core.resolve_name(name)
        self.service_class = service_class
        self.request_class = service_class._request_class
        self.response_class = service_class._response_class
        self.handler = handler
        self.error_handler = error_handler
        self._node = _node()
        self.uri = self._node.service_uri  # where clients connect (rosrpc://host:port), as rospy's
        self._node.advertise_service(self.resolved_name, service_class._type, service_class._md5sum, self._handle)

    def _handle(self, data: bytes) -> tuple[bool, bytes | str]:
        try:
            request = self.request_class().deserialize(data)
        except Exception as exc:
            return False, f"error processing request: {exc}"
        try:
            response = self.handler(request)
            if response is None:
                return False, "service cannot process request: service handler returned None"
            return True, _serialize(_to_response(response, self.response_class))
        except ServiceException as exc:
            return False, f"service cannot process request: {exc}"
        except SerializationError as exc:
            return False, f"service cannot process request: handler returned invalid value: {exc}"
        except Exception as exc:
            if self.error_handler is not None:
                self.error_handler(exc, type(exc), exc.__traceback__)
            else:
                _log.emit(_log.ERROR, "Error processing request: %s\n%s", (exc, traceback.format_exc()),
                          caller=("service.py", 0, "_handle", None))
            return False, f"error processing request: {exc}"

    def shutdown(self, reason: str = "") -> None:
        node = core.get_node()
        if node is not None:
            node.unadvertise_service(self.resolved_name)

    def spin(self) -> None:
        core.spin()


class Service(ServiceImpl):
    """Provide a service: `Service(name, service_class, handler)`."""


class ServiceProxy:
    """Call a service like a function: `proxy(request)`, `proxy(a, b)` or `proxy(a=1)`."""

    def __init__(self, name: str, service_class: type[Any], persistent: bool = False,
                 headers: dict[str, str] | None = None) -> None:
        self.resolved_name = core.resolve_name(name)
        self.service_class = service_class
        self.request_class = service_class._request_class
        self.response_class = service_class._response_class
        self.persistent = persistent
        self.headers = headers
        self._client: ServiceClient | None = None

    def wait_for_service(self, timeout: float | None = None) -> None:
        wait_for_service(self.resolved_name, timeout)

    def __call__(self, *args: Any, **kwds: Any) -> Any:
        return self.call(*args, **kwds)

    def call(self, *args: Any, **kwds: Any) -> Any:
        if self._client is None:
            master, caller_id = _master_and_caller()
            self._client = ServiceClient(master, caller_id, self.resolved_name, self.service_class._type,
                                         self.service_class._md5sum, self.persistent, self.headers)
        try:
            request = args_kwds_to_message(self.request_class, args, kwds)
            data = _serialize(request)
        except (TypeError, ValueError, AttributeError, SerializationError) as exc:
            raise ROSSerializationException(str(exc)) from exc
        try:
            answer = self._client.call(data)
        except MasterError:
            raise ServiceException(f"service [{self.resolved_name}] unavailable") from None
        except ServiceError as exc:
            raise ServiceException(str(exc)) from None
        except OSError as exc:
            raise ServiceException(f"unable to contact master: {exc}") from None
        return self.response_class().deserialize(answer)

    def close(self) -> None:
        if self._client is not None:
            self._client.close()


# A service not yet advertised sends no event: wait_for_service asks again every 20 ms (a
# server that comes up is used that soon), and shutdown ends the wait at once.
SERVICE_POLL_PERIOD = 0.02


def wait_for_service(service: str, timeout: Any = None) -> None:
    """Block until `service` answers a probe; ROSException on timeout, ROSInterruptException at shutdown."""
    master, caller_id = _master_and_caller()
    resolved = core.resolve_name(service)
    if timeout is not None and not isinstance(timeout, (int, float)):
        timeout = float(timeout.to_sec())  # a rospy.Duration, as rospy takes too
    deadline = None if timeout is None else time.monotonic() + timeout
    if timeout == 0.0:
        raise ValueError("timeout must be non-zero")
    while not core.is_shutdown():
        try:
            probe_service(master, caller_id, resolved, timeout=2.0)
            return
        except (OSError, MasterError, ServiceError, ValueError):
            pass
        if deadline is not None and time.monotonic() >= deadline:
            raise ROSException(f"timeout exceeded while waiting for service {resolved}")
        core.wait_for_shutdown(SERVICE_POLL_PERIOD)
    raise ROSInterruptException("rospy shutdown")
