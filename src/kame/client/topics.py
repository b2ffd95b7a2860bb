"""Publisher and Subscriber (rospy's) over kame's Node.

Several Publisher (or Subscriber) objects for one topic in a process share the node's one
publication (subscription), as in rospy; unregister() drops a handle, the last one the topic.
"""

from __future__ import annotations

import abc
import logging
import threading
import traceback
from collections.abc import Callable
from typing import Any

from kame.client import core
from kame.client import log as _log
from kame.client.errors import ROSException, ROSSerializationException
from kame.client.message_args import args_kwds_to_message
from kame.msg.anymsg import AnyMsg
from kame.msg.errors import SerializationError
from kame.node.topics import Publication, SubscriberLink, Subscription, serialize_frame

_file_log = logging.getLogger("rospy.topics")


class SubscribeListener:
    """Callbacks for a publisher's subscriber connections (rospy.SubscribeListener)."""

    def peer_subscribe(self, topic_name: str, topic_publish: Callable[[Any], None],
                       peer_publish: Callable[[Any], None]) -> None:
        pass

    def peer_unsubscribe(self, topic_name: str, num_peers: int) -> None:
        pass


class Topic(abc.ABC):
    def __init__(self, name: str, data_class: type[Any]) -> None:
        if not isinstance(name, str) or not name:
            raise ValueError("topic name must be a non-empty string")
        if data_class is None or not hasattr(data_class, "_type"):
            raise ValueError("data_class must be a message class")
        self.unresolved_name = name
        self.resolved_name = core.resolve_name(name)
        self.name = self.resolved_name
        self.data_class = data_class
        self.type = data_class._type
        self.md5sum = data_class._md5sum

    def _when_initialized(self) -> None:
        """Bind now, or once init_node() has run (tutorials create topics before init_node)."""
        node = core.get_node()
        if node is None:
            core.defer_until_initialized(self._bind_to)
        else:
            self._bind_to(node)

    @abc.abstractmethod
    def _bind_to(self, node: Any) -> None:
        """Register with the node: resolve the name now that remappings are known."""


_publications: dict[str, tuple[Publication, list[Publisher]]] = {}
_subscriptions: dict[str, tuple[Subscription, _Callbacks, list[Subscriber]]] = {}
_registry_lock = threading.Lock()
DEFAULT_BUFF_SIZE = 65536  # rospy's


class Publisher(Topic):
    def __init__(self, name: str, data_class: type[Any], subscriber_listener: SubscribeListener | None = None,
                 tcp_nodelay: bool = False, latch: bool = False, headers: dict[str, str] | None = None,
                 queue_size: int | None = None) -> None:
        super().__init__(name, data_class)
        if queue_size is None:
            import warnings

            warnings.warn("The publisher should be created with an explicit keyword argument 'queue_size'. "
                          "Please see http://wiki.ros.org/rospy/Overview/Publishers%20and%20Subscribers for more "
                          "information.", SyntaxWarning, stacklevel=2)
        self.latch = latch
        self.queue_size = queue_size
        self.headers = headers
        self.tcp_nodelay = tcp_nodelay
        self.impl: Publication | None = None
        self._listener = subscriber_listener
        self._unregistered = False
        self._when_initialized()

    def _bind_to(self, node: Any) -> None:
        if self._unregistered:
            return
        self.resolved_name = self.name = core.resolve_name(self.unresolved_name)
        connected, disconnected = self._listener_callbacks(self._listener) if self._listener else (None, None)
        with _registry_lock:
            entry = _publications.get(self.resolved_name)
            if entry is not None and entry[0].closed:
                entry = None
            joined = entry is not None
            if entry is None:
                impl = node.advertise(self.resolved_name, self.type, self.md5sum, self.data_class._full_text,
                                      self.latch, self.queue_size or 0, self.headers, connected, disconnected,
                                      self.tcp_nodelay)
                entry = (impl, [])
                _publications[self.resolved_name] = entry
            elif entry[0].md5sum != self.md5sum:
                raise ROSException(f"tried to publish [{self.resolved_name}] with type [{self.type}], "
                                   f"but it is already published as [{entry[0].type}]")
            entry[1].append(self)
        self.impl = entry[0]
        if joined and self.tcp_nodelay:  # as rospy: for the topic's connections from now on
            self.impl.tcp_nodelay = True
        if joined and connected is not None and disconnected is not None:
            self.impl.add_connect_callback(connected)
            self.impl.on_disconnect.append(disconnected)

    def _listener_callbacks(self, listener: SubscribeListener) -> tuple[Callable[[SubscriberLink], None],
                                                                          Callable[[SubscriberLink], None]]:
        def connected(link: SubscriberLink) -> None:
            def peer_publish(msg: Any) -> None:
                frame = serialize_frame(msg)
                link.sender.send(frame[0]) if len(frame) == 1 else link.sender.send_parts(frame)

            listener.peer_subscribe(self.resolved_name, self.publish, peer_publish)

        def disconnected(link: SubscriberLink) -> None:
            impl = self.impl
            listener.peer_unsubscribe(self.resolved_name, len(impl.links) if impl is not None else 0)

        return connected, disconnected

    def get_num_connections(self) -> int:
        return len(self.impl.links) if self.impl is not None else 0

    def publish(self, *args: Any, **kwds: Any) -> None:
        impl = self.impl
        if impl is None:
            if self._unregistered:
                raise ROSException("publish() to an unregistered() handle")
            raise ROSException("ROS node has not been initialized yet. Please call init_node() first")
        if impl.closed:
            raise ROSException("publish() to a closed topic")
        if len(args) == 1 and not kwds and type(args[0]) is self.data_class:
            msg = args[0]
        else:
            try:
                msg = args_kwds_to_message(self.data_class, args, kwds)
            except (TypeError, ValueError, AttributeError) as exc:
                raise ROSSerializationException(str(exc)) from exc
        if msg._has_header:
            msg.header.seq = impl.next_seq()
        try:
            impl.publish_message(msg)
        except SerializationError as exc:
            raise ROSSerializationException(str(exc)) from exc

    def unregister(self) -> None:
        self._unregistered = True
        impl, self.impl = self.impl, None
        if impl is None:
            return
        with _registry_lock:
            entry = _publications.get(self.resolved_name)
            if entry is None or entry[0] is not impl:
                return
            if self in entry[1]:
                entry[1].remove(self)
            if entry[1]:
                return
            del _publications[self.resolved_name]
        node = core.get_node()
        if node is not None:
            node.unadvertise(self.resolved_name)


class _Callbacks:
    """The callbacks of one subscribed topic, run for each message in arrival order."""

    def __init__(self, data_class: type[Any], entries: list[tuple[Callable[..., Any], Any, bool]]) -> None:
        self.data_class = data_class
        self.entries = entries
        self.undeserializable: dict[str, int] = {}  # publisher callerid -> messages skipped

    def deliver(self, frames: list[memoryview], header: dict[str, str]) -> None:
        entries = self.entries
        if len(frames) != 1 or len(entries) != 1 or entries[0][2]:
            self.deliver_to(entries, frames, header)
            return
        # The usual case in full, without deliver_to's and _run's loops and calls (this is on
        # every message's path): one message, one callback without arguments.
        try:
            msg = self.data_class._from_buffer(frames[0])
        except Exception as exc:
            self._undeserializable(header.get("callerid", "?"), exc)
            return
        msg._connection_header = header
        callback = entries[0][0]
        try:
            callback(msg)
        except Exception:
            self._callback_failed(callback)

    def deliver_messages(self, msgs: list[Any], header: dict[str, str]) -> None:
        """Messages published in this process, as published (kame.node.local): shared with the
        publisher and every other subscriber, so callbacks must not modify them."""
        entries = self.entries
        for msg in msgs:
            msg._connection_header = header
            self._run(entries, msg)

    def deliver_to(self, entries: list[tuple[Callable[..., Any], Any, bool]], frames: list[memoryview],
                   header: dict[str, str]) -> None:
        from_buffer = self.data_class._from_buffer
        for frame in frames:
            try:
                msg = from_buffer(frame)
            except Exception as exc:
                # As rospy: the message is skipped and the connection kept (the frames after it
                # are good TCPROS). Logged for the first message per publisher, not for each.
                self._undeserializable(header.get("callerid", "?"), exc)
                continue
            msg._connection_header = header
            self._run(entries, msg)

    @staticmethod
    def _run(entries: list[tuple[Callable[..., Any], Any, bool]], msg: Any) -> None:
        for callback, args, has_args in entries:
            try:
                if has_args:
                    callback(msg, args)
                else:
                    callback(msg)
            except Exception:
                _Callbacks._callback_failed(callback)

    @staticmethod
    def _callback_failed(callback: Callable[..., Any]) -> None:
        """Log the exception being handled, raised by `callback`."""
        if core.is_shutdown():
            # as rospy: a callback that was running as the node shut down (publishing to a
            # topic just closed) is no error for the console; the log file keeps it
            _file_log.warning("during shutdown, bad callback: %s\n%s", callback, traceback.format_exc())
            return
        _log.emit(_log.ERROR, "bad callback: %s\n%s", (callback, traceback.format_exc()),
                  caller=("topics.py", 0, "deliver", None))

    def _undeserializable(self, callerid: str, exc: Exception) -> None:
        count = self.undeserializable.get(callerid, 0)
        self.undeserializable[callerid] = count + 1
        if count == 0:
            _log.emit(_log.ERROR, "cannot deserialize a message on a subscription of type [%s] from [%s]: %s "
                      "(the message is skipped; further failures from this publisher are not logged)",
                      (self.data_class._type, callerid, exc), caller=("topics.py", 0, "deliver", None))


class Subscriber(Topic):
    def __init__(self, name: str, data_class: type[Any], callback: Callable[..., Any] | None = None,
                 callback_args: Any = None, queue_size: int | None = None, buff_size: int = DEFAULT_BUFF_SIZE,
                 tcp_nodelay: bool = False, shared_memory: bool = True) -> None:
        """`buff_size` is the bytes each read from a publisher asks for, and `tcp_nodelay` asks
        publishers to send without delay (see kame.node.topics.Subscription). `shared_memory`
        (kame's own transport hint, not rospy's) False keeps this topic on TCPROS even with
        kame publishers on this host (kame.protocol.shmros)."""
        super().__init__(name, data_class)
        if type(buff_size) is not int:
            raise ROSException("buff_size must be an integer")
        if buff_size <= 0:
            raise ROSException("buff_size must be positive")
        self.callback = callback
        self.callback_args = callback_args
        self.queue_size = queue_size
        self.tcp_nodelay = tcp_nodelay
        self.buff_size = buff_size
        self.shared_memory = shared_memory
        self.impl: Subscription | None = None
        self._unregistered = False
        self._when_initialized()

    def _bind_to(self, node: Any) -> None:
        if self._unregistered:
            return
        self.resolved_name = self.name = core.resolve_name(self.unresolved_name)
        mine: list[tuple[Callable[..., Any], Any, bool]] = []
        if self.callback is not None:
            mine.append((self.callback, self.callback_args, self.callback_args is not None))
        with _registry_lock:
            entry = _subscriptions.get(self.resolved_name)
            if entry is not None and entry[0].closed:
                entry = None
            joined = entry is not None
            if entry is None:
                # The callback is in place before the first connection starts: a latched message
                # that comes with the publisher's handshake is delivered at once, to it.
                callbacks = _Callbacks(self.data_class, mine)
                any_type = self.data_class is AnyMsg
                impl = node.subscribe(self.resolved_name, self.type, "*" if any_type else self.md5sum,
                                      "" if any_type else self.data_class._full_text, callbacks.deliver,
                                      self.queue_size, self.tcp_nodelay, self.buff_size,
                                      message_class=None if any_type else self.data_class,
                                      deliver_messages=callbacks.deliver_messages,
                                      shared_memory=self.shared_memory)
                entry = (impl, callbacks, [])
                _subscriptions[self.resolved_name] = entry
            elif self.data_class is not AnyMsg and entry[0].md5sum not in ("*", self.md5sum):
                # an AnyMsg subscriber joins whatever class the topic has (rospy's shared impl)
                raise ROSException(f"tried to subscribe to [{self.resolved_name}] as [{self.type}], "
                                   f"but it is already subscribed as [{entry[0].type}]")
            entry[2].append(self)
        self.impl = entry[0]
        self._callbacks = entry[1]
        if joined:  # as rospy: a non-default choice applies to the topic's connections from now on
            if self.tcp_nodelay:
                self.impl.tcp_nodelay = True
            if self.buff_size != DEFAULT_BUFF_SIZE:
                self.impl.buff_size = self.buff_size
        if joined and mine:
            with entry[0].callback_lock:
                entry[1].entries = [*entry[1].entries, *mine]
                for frame, header in entry[0].latched_messages():  # rospy's #1852
                    entry[1].deliver_to(mine, [memoryview(frame)], header)

    def get_num_connections(self) -> int:
        return self.impl.connection_count if self.impl is not None else 0

    def unregister(self) -> None:
        self._unregistered = True
        impl, self.impl = self.impl, None
        if impl is None:
            return
        with _registry_lock:
            cbs = self._callbacks
            with impl.callback_lock:
                cbs.entries = [e for e in cbs.entries if not (e[0] is self.callback and e[1] is self.callback_args)]
            entry = _subscriptions.get(self.resolved_name)
            if entry is None or entry[0] is not impl:
                return
            if self in entry[2]:
                entry[2].remove(self)
            if entry[2]:
                return
            del _subscriptions[self.resolved_name]
        node = core.get_node()
        if node is not None:
            node.unsubscribe(self.resolved_name)
