"""rospy.topics: Publisher and Subscriber (kame.client.topics), and the names rospy.topics
carries: rospy.core's, the topic manager, the TCPROS handler, message framing, and Poller
(which of a set of file descriptors hung up or failed)."""

from __future__ import annotations

import select
from io import BytesIO, StringIO
from itertools import chain
from typing import Any

from kame.client.errors import ROSSerializationException, TransportTerminated
from kame.client.topics import (
    Publisher,
    SubscribeListener,
    Subscriber,
    Topic,
)
from kame.msg.message import Message
from rospy.core import *  # noqa: F403  (rospy.topics re-exports rospy.core, as rospy's)
from rospy.core import __all__ as _core_names
from rospy.core import _lazy_names
from rospy.msg import args_kwds_to_message, serialize_message

# rospy.impl's names, by module: they load when first asked for (a program that only publishes
# and subscribes never loads them)
_IMPL = {"Registration": "registration", "get_registration_listeners": "registration",
         "get_topic_manager": "registration", "set_topic_manager": "registration",
         "SubscriberStatisticsLogger": "statistics", "DEFAULT_BUFF_SIZE": "tcpros", "get_tcpros_handler": "tcpros",
         "QueuedConnection": "tcpros_pubsub"}

__all__ = [*_core_names, *_IMPL, "BytesIO", "Message", "Poller", "Publisher", "ROSSerializationException", "StringIO",
           "SubscribeListener", "Subscriber", "Topic", "TransportTerminated", "args_kwds_to_message", "chain",
           "python3", "serialize_message"]

python3 = 1

_ERRORS = select.EPOLLHUP | select.EPOLLERR | select.EPOLLRDHUP


class Poller:
    """File descriptors watched for a hang-up or an error (epoll): error_iter() yields those
    that have one now, without waiting."""

    def __init__(self) -> None:
        self.poller = select.epoll()

    def add_fd(self, fd: int) -> None:
        self.poller.register(fd, _ERRORS)

    def remove_fd(self, fd: int) -> None:
        self.poller.unregister(fd)

    def error_iter(self) -> Any:
        for fd, event in self.poller.poll(0):
            if event & _ERRORS:
                yield fd


__getattr__ = _lazy_names(__name__, {name: (f"rospy.impl.{module}", name) for name, module in _IMPL.items()})
