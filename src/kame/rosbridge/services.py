"""The bridge's services: a client calling a ROS service, and a ROS service a client provides.

- call_service: the type is the one given, else the service's own (its probe header); `args` is
  an object of the request's fields or a list of them in order. The answer is a
  service_response op, result false with the error text as values when the call fails.
- advertise_service: a ROS service whose every call goes to the client as a call_service op
  with an id of its own ("service_request:<service>:<n>") and waits for the client's
  service_response of that id; the call fails if the client unadvertises the service or goes.
"""

from __future__ import annotations

import threading
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

from kame.client.errors import ROSException
from kame.client.services import Service, ServiceException, ServiceProxy
from kame.msg.errors import MessageError
from kame.msg.lookup import service_class
from kame.rosbridge import conversion
from kame.rosbridge.graph import Graph
from kame.rosbridge.topics import ros_now

if TYPE_CHECKING:
    from kame.rosbridge.session import Session


def _request(request_class: Any, args: Any) -> Any:
    if isinstance(args, list):
        if len(args) > len(request_class.__slots__):
            raise conversion.ConversionError(
                f"{request_class._type} takes {len(request_class.__slots__)} arguments, got {len(args)}")
        args = dict(zip(request_class.__slots__, args, strict=False))
    return conversion.from_json(request_class, args, ros_now)


def call_service(graph: Graph, service: str, type_name: str, args: Any, op_id: Any) -> dict[str, Any]:
    """The service_response op answering a client's call_service."""
    answer: dict[str, Any] = {"op": "service_response", "service": service, "result": False}
    if op_id is not None:
        answer["id"] = op_id
    chosen = type_name or graph.service_type(service)
    if not chosen:
        answer["values"] = f"Service {service} does not exist"
        return answer
    srv = service_class(chosen)
    if srv is None:
        answer["values"] = f"Unable to load the service class for type '{chosen}': no such type"
        return answer
    proxy = ServiceProxy(service, srv)
    try:
        response = proxy.call(_request(srv._request_class, args))
    except (ServiceException, ROSException, MessageError, conversion.ConversionError) as exc:
        answer["values"] = str(exc)
        return answer
    finally:
        proxy.close()
    answer["values"] = conversion.to_json(response)
    answer["result"] = True
    return answer


class _Pending:
    def __init__(self) -> None:
        self.done = threading.Event()
        self.values: Any = None
        self.result = False


class AdvertisedService:
    """A ROS service that the client `session` provides."""

    def __init__(self, session: Session, name: str, srv: Any, request_ids: Iterator[int]) -> None:
        self.session = session
        self.name = name
        self.srv = srv
        self._ids = request_ids
        self._pending: dict[str, _Pending] = {}
        self._lock = threading.Lock()
        self._closed = False
        self.service = Service(name, srv, self._handle)

    def _handle(self, request: Any) -> Any:
        request_id = f"service_request:{self.name}:{next(self._ids)}"
        pending = _Pending()
        with self._lock:
            if self._closed:
                raise ServiceException(f"service {self.name} is no longer provided")
            self._pending[request_id] = pending
        sent = self.session.send_op({"op": "call_service", "id": request_id, "service": self.name,
                                     "args": conversion.to_json(request)})
        if sent:
            pending.done.wait()
        with self._lock:
            self._pending.pop(request_id, None)
        if not sent or not pending.result:
            reason = pending.values if isinstance(pending.values, str) else "the client's service failed"
            raise ServiceException(reason if pending.done.is_set() else f"service {self.name} is no longer provided")
        try:
            return conversion.from_json(self.srv._response_class, pending.values or {}, ros_now)
        except conversion.ConversionError as exc:
            raise ServiceException(f"the client's response does not fit {self.srv._type}: {exc}") from None

    def answer(self, request_id: Any, values: Any, result: bool) -> bool:
        """The client's service_response; False when no call of that id waits."""
        with self._lock:
            pending = self._pending.get(str(request_id))
        if pending is None:
            return False
        pending.values, pending.result = values, result
        pending.done.set()
        return True

    def close(self) -> None:
        """Unadvertise; calls still waiting fail."""
        with self._lock:
            self._closed = True
            waiting = list(self._pending.values())
        self.service.shutdown()
        for pending in waiting:
            pending.values, pending.result = f"service {self.name} is no longer provided", False
            pending.done.set()
