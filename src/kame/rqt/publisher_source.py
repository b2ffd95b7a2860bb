"""rqt_publisher's sending side: a topic advertised on the tool's node for each publisher the user
adds, and messages built from the field expressions (message_tree.build_message) and sent.
The window's timers say when; nothing here waits."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from kame.msg.lookup import message_class as load_message_class
from kame.node.node import Node
from kame.node.topics import serialize_frame
from kame.rqt.message_tree import ExpressionError, build_message


class PublisherError(ValueError):
    """A type kame cannot load, a topic already published with another type, a message that does not fit."""


class MessagePublisher:
    def __init__(self, node: Node) -> None:
        self.node = node
        self.classes: dict[str, type[Any]] = {}  # topic -> its message class

    def topic_types(self) -> list[tuple[str, str]]:
        return sorted((str(t), str(ty)) for t, ty in self.node.master.call("getTopicTypes"))

    def add(self, topic: str, type_name: str) -> type[Any]:
        """Advertise `topic` as `type_name`; returns the message class."""
        topic = self.node.resolve(topic)
        cls = load_message_class(type_name)
        if cls is None:
            raise PublisherError(f"unknown message type {type_name!r}")
        known = self.classes.get(topic)
        if known is not None and known is not cls:
            raise PublisherError(f"{topic} is published here as {known._type} already")
        self.node.advertise(topic, cls._type, cls._md5sum, cls._full_text, queue_size=100)
        self.classes[topic] = cls
        return cls

    def publish(self, topic: str, expressions: Mapping[str, str], i: int) -> Any:
        """Send one message; returns it. PublisherError names the field that did not fit."""
        cls = self.classes[topic]
        try:
            message = build_message(cls, expressions, i)
            frame = serialize_frame(message)
        except ExpressionError as exc:
            raise PublisherError(str(exc)) from exc
        except Exception as exc:  # the serializer's type check: a value of the wrong type
            raise PublisherError(f"{topic}: {exc}") from exc
        self.node.publications[topic].publish_frame(frame)
        return message

    def remove(self, topic: str) -> None:
        if self.classes.pop(topic, None) is not None:
            self.node.unadvertise(topic)

    def close(self) -> None:
        for topic in list(self.classes):
            self.remove(topic)
