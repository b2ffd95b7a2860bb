"""What the bridge and rosapi ask the master and the services: names, types, providers.

One object over the program's node (kame.client): topic types from getTopicTypes, a service's
type from its probe header (as rosservice learns it), the system state and the parameters.
"""

from __future__ import annotations

from typing import Any

from kame import names
from kame.client import core
from kame.client.process import get_master
from kame.net.handshake import HandshakeError
from kame.node.master_proxy import MasterError
from kame.node.services import ServiceError, parse_rosrpc, probe_service

PROBE_TIMEOUT = 5.0


class Graph:
    def resolve(self, name: str) -> str:
        """A client's name: absolute as given, else relative to the root (the bridge's namespace)."""
        if not name:
            raise ValueError("empty name")
        return names.canonicalize(name if name.startswith("/") else "/" + name)

    def master(self) -> Any:
        return get_master()

    def topic_types(self) -> list[tuple[str, str]]:
        return [(str(t), str(ty)) for t, ty in self.master().call("getTopicTypes")]

    def topic_type(self, topic: str) -> str:
        return next((ty for t, ty in self.topic_types() if t == topic), "")

    def system_state(self) -> tuple[list[Any], list[Any], list[Any]]:
        publishers, subscribers, services = self.master().call("getSystemState")
        return publishers, subscribers, services

    def service_uri(self, service: str) -> str | None:
        try:
            return str(self.master().call("lookupService", service))
        except MasterError:
            return None

    def service_type(self, service: str) -> str:
        """The type a service's probe header names; "" when it is not there or does not answer."""
        try:
            header = probe_service(self.master(), core.get_caller_id(), service, PROBE_TIMEOUT)
        except (MasterError, OSError, ServiceError, HandshakeError, ValueError):
            return ""
        return header.get("type", "")

    def service_host(self, service: str) -> str:
        uri = self.service_uri(service)
        if uri is None:
            return ""
        host, _ = parse_rosrpc(uri)
        return host
