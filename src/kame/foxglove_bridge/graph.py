"""What the bridge offers its clients, kept in step with the ROS graph (no I/O: the master's
answers in, the changes to announce out).

- A channel per published (topic, type) whose topic matches the topic whitelist and whose type
  has a definition (`schema_of`: the full ros1msg text, as a connection header's
  message_definition); ids are never reused, so a client never confuses an old channel with a
  new one.
- A service per advertised name matching the service whitelist, once its type is known (the
  bridge asks the service itself, as rosservice does).
- The connection graph: who publishes, subscribes and provides what, and what disappeared since
  the last update.
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

from kame.foxglove_bridge.protocol import Channel, ServiceInfo


def compile_whitelist(patterns: Iterable[str]) -> tuple[list[re.Pattern[str]], list[str]]:
    """The patterns that compile, and the ones that do not (for one error line each)."""
    good, bad = [], []
    for pattern in patterns:
        try:
            good.append(re.compile(str(pattern)))
        except re.error:
            bad.append(str(pattern))
    return good, bad


def allowed(name: str, whitelist: list[re.Pattern[str]]) -> bool:
    return any(p.fullmatch(name) for p in whitelist)


@dataclass(frozen=True)
class SystemState:
    publishers: dict[str, list[str]]
    subscribers: dict[str, list[str]]
    services: dict[str, list[str]]
    topic_types: dict[str, str]

    @classmethod
    def from_master(cls, state: list[list[list[Any]]], types: list[list[str]]) -> SystemState:
        """From getSystemState's and getTopicTypes' answers."""
        def table(rows: list[list[Any]]) -> dict[str, list[str]]:
            return {str(row[0]): sorted(str(n) for n in row[1]) for row in rows}

        return cls(table(state[0]), table(state[1]), table(state[2]), {str(t): str(k) for t, k in types})


@dataclass
class ChannelChanges:
    added: list[Channel] = field(default_factory=list)
    removed: list[int] = field(default_factory=list)


@dataclass
class ServiceChanges:
    added: list[ServiceInfo] = field(default_factory=list)
    removed: list[int] = field(default_factory=list)


class Offer:
    def __init__(self, topic_whitelist: list[re.Pattern[str]], service_whitelist: list[re.Pattern[str]],
                 schema_of: Callable[[str], str | None]) -> None:
        self._topics = topic_whitelist
        self._services = service_whitelist
        self._schema_of = schema_of
        self._channel_ids = itertools.count(1)
        self._service_ids = itertools.count(1)
        self.channels: dict[tuple[str, str], Channel] = {}
        self.services: dict[str, ServiceInfo] = {}
        self.unknown_types: set[str] = set()  # types with no definition here, already reported
        self._graph: tuple[dict[str, list[str]], dict[str, list[str]], dict[str, list[str]]] | None = None

    def channel(self, channel_id: int) -> Channel | None:
        return next((c for c in self.channels.values() if c.id == channel_id), None)

    def service(self, service_id: int) -> ServiceInfo | None:
        return next((s for s in self.services.values() if s.id == service_id), None)

    def update_channels(self, state: SystemState) -> tuple[ChannelChanges, list[str]]:
        """The channels to advertise and unadvertise, and types newly found to have no definition."""
        changes, unknown = ChannelChanges(), []
        wanted = {(topic, state.topic_types[topic]) for topic in state.publishers
                  if topic in state.topic_types and allowed(topic, self._topics)}
        for key in sorted(wanted - self.channels.keys()):
            schema = self._schema_of(key[1])
            if schema is None:
                if key[1] not in self.unknown_types:
                    self.unknown_types.add(key[1])
                    unknown.append(key[1])
                continue
            channel = Channel(next(self._channel_ids), key[0], key[1], schema)
            self.channels[key] = channel
            changes.added.append(channel)
        for key in sorted(self.channels.keys() - wanted):
            changes.removed.append(self.channels.pop(key).id)
        return changes, unknown

    def services_to_describe(self, state: SystemState) -> list[str]:
        return sorted(n for n in state.services if n not in self.services and allowed(n, self._services))

    def update_services(self, state: SystemState, described: dict[str, ServiceInfo | None]) -> ServiceChanges:
        """`described`: what each name of services_to_describe turned out to be (None: unknown)."""
        changes = ServiceChanges()
        for name in sorted(described):
            info = described[name]
            if info is not None and name in state.services:
                info = ServiceInfo(next(self._service_ids), name, info.type, info.request_schema, info.response_schema)
                self.services[name] = info
                changes.added.append(info)
        for name in sorted(self.services.keys() - state.services.keys()):
            changes.removed.append(self.services.pop(name).id)
        return changes

    def graph_update(self, state: SystemState) -> tuple[dict[str, list[str]], dict[str, list[str]],
                                                        dict[str, list[str]], list[str], list[str]] | None:
        """The connection graph's update since the last one (None: nothing changed)."""
        graph = (state.publishers, state.subscribers, state.services)
        previous = self._graph
        self._graph = graph
        if previous == graph:
            return None
        if previous is None:
            return (*graph, [], [])
        topics_before = previous[0].keys() | previous[1].keys()
        topics_now = graph[0].keys() | graph[1].keys()
        return (*graph, sorted(topics_before - topics_now), sorted(previous[2].keys() - graph[2].keys()))
