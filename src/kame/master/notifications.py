"""What the master must tell nodes after a change: plain values that the server sends.

The pure core returns these instead of calling anyone, so it never waits on a node. Each carries
the XML-RPC URI to call and the arguments after the caller_id (which is always `/master`).
"""

from __future__ import annotations

from dataclasses import dataclass

from kame.protocol.xmlrpc import Value


@dataclass(frozen=True)
class PublisherUpdate:
    """`publisherUpdate('/master', topic, publishers)`: always the complete list, never a delta."""

    node_api: str
    topic: str
    publishers: tuple[str, ...]

    @property
    def call(self) -> tuple[str, list[Value]]:
        return "publisherUpdate", ["/master", self.topic, list(self.publishers)]


@dataclass(frozen=True)
class ParamUpdate:
    """`paramUpdate('/master', key, value)`: key with a trailing slash, `{}` for a deletion."""

    node_api: str
    key: str
    value: Value

    @property
    def call(self) -> tuple[str, list[Value]]:
        return "paramUpdate", ["/master", self.key, self.value]


@dataclass(frozen=True)
class ShutdownNode:
    """`shutdown('/master', reason)`: sent to a node whose name another node has taken."""

    node_api: str
    reason: str

    @property
    def call(self) -> tuple[str, list[Value]]:
        return "shutdown", ["/master", self.reason]


Notification = PublisherUpdate | ParamUpdate | ShutdownNode
