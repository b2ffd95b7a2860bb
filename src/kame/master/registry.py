"""The master's registrations: publishers, subscribers, services, parameter subscribers, nodes.

Rules (ros1-interop spec §1.3, §3; rosmaster 1.15.15 registrations.py):
- A node is known by its caller_id and its XML-RPC URI. It stays known (lookupNode) while it
  holds at least one registration of any kind, parameter subscriptions included.
- A registration from a known caller_id with a different URI is a new node taking the name: the
  old URI is told to shut down and every registration of that caller_id is dropped, without any
  publisherUpdate for the publications that vanish.
- One provider per service; a new registration replaces the old one silently. The old provider
  still counts the service as its own (rosmaster keeps it in the node's list), so it stays known.
- Registration order is kept (dicts), because getSystemState and the URI lists show it.
- Unregistering something not registered succeeds with value 0.
- Topic types are recorded by publishers (overwriting, except with `*`) and by subscribers (only
  if unknown and not `*`), and are never forgotten.
Names arrive already resolved; checking and resolving them is the API layer's job.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from kame.master.notifications import Notification, PublisherUpdate, ShutdownNode
from kame.names import ANY_TYPE

#: The `[code, message, value]` triple an unregister call answers with.
Status = tuple[int, str, int]


@dataclass
class _Node:
    api: str
    publications: set[str] = field(default_factory=set)
    subscriptions: set[str] = field(default_factory=set)
    services: set[str] = field(default_factory=set)
    param_subscriptions: set[str] = field(default_factory=set)

    def is_empty(self) -> bool:
        return not (self.publications or self.subscriptions or self.services or self.param_subscriptions)


@dataclass(frozen=True)
class _Service:
    caller_id: str
    caller_api: str
    service_api: str


# key (topic or parameter) -> {caller_id: caller_api}, both in registration order
_Table = dict[str, dict[str, str]]


class Registry:
    def __init__(self) -> None:
        self._nodes: dict[str, _Node] = {}
        self._publishers: _Table = {}
        self._subscribers: _Table = {}
        self._param_subscribers: _Table = {}
        self._services: dict[str, _Service] = {}
        self._topic_types: dict[str, str] = {}
        self._any_service = False  # rosmaster words an unregisterService miss differently before

    # ---------------------------------------------------------------------------- topics

    def register_publisher(
        self, topic: str, topic_type: str, caller_id: str, caller_api: str
    ) -> tuple[list[str], list[Notification]]:
        """Returns the topic's subscriber URIs and the notifications to send."""
        notes = self._claim(caller_id, caller_api)
        self._nodes[caller_id].publications.add(topic)
        self._publishers.setdefault(topic, {})[caller_id] = caller_api
        if topic_type != ANY_TYPE or topic not in self._topic_types:
            self._topic_types[topic] = topic_type
        subscribers = list(self._subscribers.get(topic, {}).values())
        notes.extend(self._publisher_updates(topic, subscribers))
        return subscribers, notes

    def unregister_publisher(
        self, topic: str, caller_id: str, caller_api: str
    ) -> tuple[Status, list[Notification]]:
        status = self._unregister(self._publishers, "publications", topic, caller_id, caller_api)
        if not status[2]:
            return status, []
        subscribers = list(self._subscribers.get(topic, {}).values())
        return status, list(self._publisher_updates(topic, subscribers))

    def register_subscriber(
        self, topic: str, topic_type: str, caller_id: str, caller_api: str
    ) -> tuple[list[str], list[Notification]]:
        """Returns the topic's publisher URIs and the notifications to send."""
        notes = self._claim(caller_id, caller_api)
        self._nodes[caller_id].subscriptions.add(topic)
        self._subscribers.setdefault(topic, {})[caller_id] = caller_api
        if topic_type != ANY_TYPE and topic not in self._topic_types:
            self._topic_types[topic] = topic_type
        return list(self._publishers.get(topic, {}).values()), notes

    def unregister_subscriber(self, topic: str, caller_id: str, caller_api: str) -> Status:
        return self._unregister(self._subscribers, "subscriptions", topic, caller_id, caller_api)

    def _publisher_updates(self, topic: str, subscriber_apis: list[str]) -> list[Notification]:
        if not subscriber_apis:
            return []
        publishers = tuple(self._publishers.get(topic, {}).values())
        return [PublisherUpdate(api, topic, publishers) for api in subscriber_apis]

    # ---------------------------------------------------------------------------- services

    def register_service(
        self, service: str, service_api: str, caller_id: str, caller_api: str
    ) -> list[Notification]:
        notes = self._claim(caller_id, caller_api)
        self._nodes[caller_id].services.add(service)
        self._services[service] = _Service(caller_id, caller_api, service_api)
        self._any_service = True
        return notes

    def unregister_service(self, service: str, service_api: str, caller_id: str) -> Status:
        node = self._nodes.get(caller_id)
        if node is None:
            return 1, f"[{caller_id}] is not a registered node", 0
        current = self._services.get(service)
        if not self._any_service:
            status: Status = (1, f"[{caller_id}] is not a provider of [{service}]", 0)
        elif current is None or current.caller_id != caller_id or current.service_api != service_api:
            message = f"[{service_api}] is no longer the current service api handle for [{service}]"
            status = (1, message, 0)
        else:
            del self._services[service]
            node.services.discard(service)
            status = (1, f"Unregistered [{caller_id}] as provider of [{service}]", 1)
        if node.is_empty():
            del self._nodes[caller_id]
        return status

    def lookup_service(self, service: str) -> str | None:
        s = self._services.get(service)
        return s.service_api if s is not None else None

    # ---------------------------------------------------------------------------- parameters

    def register_param_subscriber(self, key: str, caller_id: str, caller_api: str) -> list[Notification]:
        notes = self._claim(caller_id, caller_api)
        self._nodes[caller_id].param_subscriptions.add(key)
        self._param_subscribers.setdefault(key, {})[caller_id] = caller_api
        return notes

    def unregister_param_subscriber(self, key: str, caller_id: str, caller_api: str) -> Status:
        return self._unregister(self._param_subscribers, "param_subscriptions", key, caller_id, caller_api)

    @property
    def param_subscribers(self) -> Mapping[str, Mapping[str, str]]:
        """Subscribed parameter key (with trailing slash) -> {caller_id: caller_api}."""
        return self._param_subscribers

    # ---------------------------------------------------------------------------- introspection

    def lookup_node(self, caller_id: str) -> str | None:
        node = self._nodes.get(caller_id)
        return node.api if node is not None else None

    def published_topics(self, prefix: str) -> list[list[str]]:
        """[[topic, type], ...] for topics with publishers whose name starts with `prefix`."""
        types = self._topic_types
        return [[t, types[t]] for t in self._publishers if t.startswith(prefix)]

    def topic_types(self) -> list[list[str]]:
        return [[t, ty] for t, ty in self._topic_types.items()]

    def system_state(self) -> list[list[list[str | list[str]]]]:
        return [
            [[t, list(regs)] for t, regs in self._publishers.items()],
            [[t, list(regs)] for t, regs in self._subscribers.items()],
            [[s, [reg.caller_id]] for s, reg in self._services.items()],
        ]

    # ---------------------------------------------------------------------------- internals

    def _claim(self, caller_id: str, caller_api: str) -> list[Notification]:
        """Make sure `caller_id` is registered at `caller_api`, bumping an older holder of the name."""
        node = self._nodes.get(caller_id)
        if node is not None and node.api == caller_api:
            return []
        notes: list[Notification] = []
        if node is not None:
            notes.append(ShutdownNode(node.api, f"[{caller_id}] Reason: new node registered with same name"))
            self._drop(caller_id, node)
        self._nodes[caller_id] = _Node(caller_api)
        return notes

    def _drop(self, caller_id: str, node: _Node) -> None:
        for table, keys in ((self._publishers, node.publications), (self._subscribers, node.subscriptions),
                            (self._param_subscribers, node.param_subscriptions)):
            for key in keys:
                regs = table.get(key)
                if regs is not None and regs.pop(caller_id, None) is not None and not regs:
                    del table[key]
        for service in node.services:
            current = self._services.get(service)
            if current is not None and current.caller_id == caller_id:
                del self._services[service]

    def _unregister(self, table: _Table, kind: str, key: str, caller_id: str, caller_api: str) -> Status:
        node = self._nodes.get(caller_id)
        if node is None:
            return 1, f"[{caller_id}] is not a registered node", 0
        regs = table.get(key)
        if regs is not None and regs.get(caller_id) == caller_api:
            del regs[caller_id]
            if not regs:
                del table[key]
            keys: set[str] = getattr(node, kind)
            keys.discard(key)
            status: Status = (1, f"Unregistered [{caller_id}] as provider of [{key}]", 1)
        else:
            status = (1, f"[{caller_id}] is not a known provider of [{key}]", 0)
        if node.is_empty():
            del self._nodes[caller_id]
        return status
