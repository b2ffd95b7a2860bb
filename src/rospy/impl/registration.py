"""rospy.impl.registration: what this process's node has registered, read from kame's Node.

get_topic_manager() answers as rospy's topic manager does (`[[topic, type], ...]`); before
init_node it has nothing registered.
"""

from __future__ import annotations

from typing import Any

from kame.client import core

__all__ = ["Registration", "TopicManager", "get_topic_manager"]


class Registration:
    """Registration kinds."""

    PUB = "pub"
    SUB = "sub"
    SRV = "srv"


class TopicManager:
    """The node's publications and subscriptions (rospy.topics' _TopicManager, read-only)."""

    @staticmethod
    def _table(kind: str) -> dict[str, Any]:
        node = core.get_node()
        if node is None:
            return {}
        return dict(node.publications if kind == Registration.PUB else node.subscriptions)

    def get_publications(self) -> list[list[str]]:
        return [[topic, pub.type] for topic, pub in self._table(Registration.PUB).items()]

    def get_subscriptions(self) -> list[list[str]]:
        return [[topic, sub.type] for topic, sub in self._table(Registration.SUB).items()]

    def has_publication(self, resolved_name: str) -> bool:
        return resolved_name in self._table(Registration.PUB)

    def has_subscription(self, resolved_name: str) -> bool:
        return resolved_name in self._table(Registration.SUB)

    def get_topics(self) -> list[str]:
        return sorted(set(self._table(Registration.PUB)) | set(self._table(Registration.SUB)))


_topic_manager = TopicManager()


def get_topic_manager() -> TopicManager:
    return _topic_manager
