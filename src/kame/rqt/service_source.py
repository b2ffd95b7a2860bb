"""rqt_service_caller's calls: the services the master knows, a service's type (asked of the
service itself, as rosservice type does), and a call with a request built from field
expressions. Calls have a timeout; the window makes them on its worker thread."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from kame.msg import lookup
from kame.msg.errors import MessageError
from kame.node.master_proxy import MasterError
from kame.node.node import Node
from kame.node.services import ServiceError, probe_service
from kame.node.topics import serialize_payload
from kame.protocol.xmlrpc import XmlRpcError
from kame.rqt.message_tree import ExpressionError, build_message

CALL_TIMEOUT = 5.0


class CallError(Exception):
    """The service is gone, hung, refused the request, or its type is not known here."""


class ServiceCaller:
    def __init__(self, node: Node, timeout: float = CALL_TIMEOUT) -> None:
        self.node = node
        self.timeout = timeout

    def services(self) -> list[str]:
        return sorted(str(name) for name, _ in self.node.master.call("getSystemState")[2])

    def service_class(self, service: str) -> Any:
        try:
            header = probe_service(self.node.master, self.node.name, service, self.timeout)
        except (OSError, MasterError, XmlRpcError, ServiceError) as exc:
            raise CallError(f"cannot reach {service}: {exc}") from exc
        type_name = header.get("type", "")
        try:
            cls = lookup.service_class(type_name)
        except MessageError:
            cls = None
        if cls is None:
            raise CallError(f"{service}: unknown service type {type_name!r}")
        return cls

    def call(self, service: str, cls: Any, expressions: Mapping[str, str]) -> Any:
        """The response to the request the expressions make (i is 0)."""
        try:
            request = build_message(cls._request_class, expressions)
            payload = serialize_payload(request)
        except ExpressionError as exc:
            raise CallError(str(exc)) from exc
        except Exception as exc:  # the serializer's type check
            raise CallError(f"the request does not fit {cls._type}: {exc}") from exc
        client = self.node.service_client(service, cls._type, cls._md5sum)
        try:
            answer = client.call(payload, timeout=self.timeout)
        except (OSError, ServiceError, MasterError, XmlRpcError) as exc:
            raise CallError(f"{service}: {exc}") from exc
        finally:
            client.close()
        return cls._response_class().deserialize(answer)
