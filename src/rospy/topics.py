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
from rospy.impl.registration import Registration, get_registration_listeners, get_topic_manager, set_topic_manager
from rospy.impl.statistics import SubscriberStatisticsLogger
from rospy.impl.tcpros import DEFAULT_BUFF_SIZE, get_tcpros_handler
from rospy.impl.tcpros_pubsub import QueuedConnection
from rospy.msg import args_kwds_to_message, serialize_message

__all__ = [*_core_names, "DEFAULT_BUFF_SIZE", "BytesIO", "Message", "Poller", "Publisher", "QueuedConnection",
           "ROSSerializationException", "Registration", "StringIO", "SubscribeListener", "Subscriber",
           "SubscriberStatisticsLogger", "Topic", "TransportTerminated", "args_kwds_to_message", "chain",
           "get_registration_listeners", "get_tcpros_handler", "get_topic_manager", "python3", "serialize_message",
           "set_topic_manager"]

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


__getattr__ = _lazy_names(__name__)
