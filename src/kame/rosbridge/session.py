"""One rosbridge client: its ops acted on against ROS, and its answers.

Every op a client sends is handled in order on the client's own thread, but for call_service,
which runs on the bridge's worker pool (a call may wait on a service this same client provides).
Whatever goes wrong with one op (malformed frame, unknown op, wrong field kinds, a type that does
not exist, a message that does not fit its type, a refused call) is a status error to that client,
echoing the op's id; the client and everyone else go on being served.
With ~authenticate, a client's ops wait for its auth op (kame.rosbridge.auth): any other op
first, or a MAC that /authenticate refuses, closes the connection, as Noetic's bridge does.
"""

from __future__ import annotations

import itertools
import logging
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any

from kame.client import log as client_log
from kame.client.errors import ROSException
from kame.client.topics import Publisher
from kame.msg.errors import MessageError
from kame.msg.lookup import message_class, service_class
from kame.msg.message import Message
from kame.rosbridge import auth, conversion, globs, protocol
from kame.rosbridge.graph import Graph
from kame.rosbridge.services import AdvertisedService, call_service
from kame.rosbridge.topics import ClientSubscription, Latest, Pacer, SubscribeOptions, ros_now

log = logging.getLogger("kame.rosbridge")
MAX_QUEUE_LENGTH = 1000  # a subscription's queue_length is at most this (its messages are held for the client)
MAX_CALLS_IN_PROGRESS = 32  # a client's call_service ops waiting or running; past it, a status error


@dataclass
class Shared:
    """What all clients of one bridge share."""

    graph: Graph
    latest: Latest
    pacer: Pacer
    workers: ThreadPoolExecutor
    max_message_size: int
    topics_glob: tuple[str, ...] | None = None
    services_glob: tuple[str, ...] | None = None
    authenticate: bool = False  # ~authenticate: every client's first op must be a good auth
    advertised_services: dict[str, AdvertisedService] = field(default_factory=dict)
    lock: threading.Lock = field(default_factory=threading.Lock)


class Session:
    def __init__(self, shared: Shared, send: Callable[[str | bytes], bool], peer: str,
                 close: Callable[[], None] | None = None) -> None:
        self.shared = shared
        self._send = send
        self._close = close
        self.peer = peer
        self.awaiting_auth = shared.authenticate
        self.status_level = protocol.DEFAULT_STATUS_LEVEL
        self.subscriptions: dict[str, ClientSubscription] = {}
        self.publishers: dict[str, Publisher] = {}
        self.services: dict[str, AdvertisedService] = {}
        self.defragmenter = protocol.Defragmenter(shared.max_message_size)
        self._lock = threading.Lock()
        self._request_ids = itertools.count(1)
        self._calls_in_progress = 0
        self._ops: dict[str, Callable[[protocol.Fields], None]] = {
            "advertise": self._advertise, "unadvertise": self._unadvertise, "publish": self._publish,
            "subscribe": self._subscribe, "unsubscribe": self._unsubscribe, "call_service": self._call_service,
            "advertise_service": self._advertise_service, "unadvertise_service": self._unadvertise_service,
            "service_response": self._service_response, "set_level": self._set_level, "fragment": self._fragment,
        }

    # ------------------------------------------------------------------ frames in, frames out

    def on_frame(self, frame: str | bytes) -> None:
        try:
            op = protocol.decode_frame(frame)
            if self.awaiting_auth:
                self._authenticate(op)
            else:
                self._dispatch(op)
        except protocol.ProtocolError as exc:
            self.status("error", str(exc), exc.op_id)

    def _authenticate(self, op: dict[str, Any]) -> None:
        if op.get("op") == "auth" and auth.authenticated(op):
            self.awaiting_auth = False
            client_log.emit(client_log.INFO, "Client %s has authenticated.", (self.peer,))
            return
        client_log.emit(client_log.WARN, "Client %s did not authenticate. Closing connection.", (self.peer,))
        if self._close is not None:
            self._close()

    def _dispatch(self, op: dict[str, Any]) -> None:
        fields = protocol.Fields(op)
        handler = self._ops.get(fields.name)
        if handler is None:
            raise protocol.ProtocolError(
                f"Unknown operation: {fields.name}. Allowed operations: {', '.join(sorted(self._ops))}",
                fields.name, fields.id)
        try:
            handler(fields)
        except protocol.ProtocolError:
            raise
        except (conversion.ConversionError, MessageError, ROSException, ValueError, TypeError) as exc:
            raise protocol.ProtocolError(f"{fields.name}: {exc}", fields.name, fields.id) from None

    def send_op(self, op: dict[str, Any]) -> bool:
        return self._send(protocol.encode_json(op))

    def send_frame(self, frame: str | bytes) -> bool:
        return self._send(frame)

    def status(self, level: str, message: str, op_id: Any = None) -> None:
        if level == "error":  # at most one line a second, whatever a client sends
            client_log.emit_throttle(1.0, client_log.WARN, "[Client %s] %s", (self.peer, message))
        if protocol.wants_status(self.status_level, level):
            self.send_op(protocol.status(level, message, op_id))

    # ------------------------------------------------------------------ topics

    def _topic(self, fields: protocol.Fields) -> str:
        topic = self.shared.graph.resolve(fields.string("topic"))
        if not globs.allows(self.shared.topics_glob, topic):
            raise protocol.ProtocolError(f"{fields.name}: topic {topic} is not allowed (topics_glob)", fields.name,
                                         fields.id)
        return topic

    def _service(self, fields: protocol.Fields) -> str:
        service = self.shared.graph.resolve(fields.string("service"))
        if not globs.allows(self.shared.services_glob, service):
            raise protocol.ProtocolError(f"{fields.name}: service {service} is not allowed (services_glob)",
                                         fields.name, fields.id)
        return service

    def _message_class(self, type_name: str) -> type[Message]:
        cls = message_class(type_name)
        if cls is None:
            raise protocol.ProtocolError(f"Unable to load the message class for type '{type_name}': no such type")
        return cls

    def _topic_class(self, topic: str, type_name: str) -> type[Message]:
        known = self.shared.graph.topic_type(topic)
        if type_name and known and known != type_name:
            raise protocol.ProtocolError(
                f"Tried to use topic {topic} with type {type_name}, but it already has type {known}")
        chosen = type_name or known
        if not chosen:
            raise protocol.ProtocolError(
                f"Cannot infer topic type for topic {topic} as it is not yet advertised")
        return self._message_class(chosen)

    def _advertise(self, fields: protocol.Fields) -> None:
        topic = self._topic(fields)
        cls = self._topic_class(topic, fields.string("type"))
        self._publisher(topic, cls, fields.boolean("latch", False), fields.integer("queue_size", 100) or 100)

    def _publisher(self, topic: str, cls: type[Message], latch: bool, queue_size: int) -> Publisher:
        with self._lock:
            existing = self.publishers.get(topic)
            if existing is not None:
                if existing.data_class is not cls:
                    raise protocol.ProtocolError(
                        f"Tried to register topic {topic} with type {cls._type} but it is already "
                        f"established with type {existing.data_class._type}")
                return existing
            publisher = Publisher(topic, cls, latch=latch, queue_size=queue_size)
            self.publishers[topic] = publisher
            return publisher

    def _unadvertise(self, fields: protocol.Fields) -> None:
        topic = self._topic(fields)
        with self._lock:
            publisher = self.publishers.pop(topic, None)
        if publisher is not None:
            publisher.unregister()

    def _publish(self, fields: protocol.Fields) -> None:
        topic = self._topic(fields)
        publisher = self.publishers.get(topic)
        if publisher is None:
            cls = self._topic_class(topic, "")
            publisher = self._publisher(topic, cls, fields.boolean("latch", False),
                                        fields.integer("queue_size", 100) or 100)
        msg = conversion.from_json(publisher.data_class, fields.op.get("msg"), ros_now)
        publisher.publish(msg)

    def _subscribe(self, fields: protocol.Fields) -> None:
        topic = self._topic(fields)
        queue_length = min(fields.integer("queue_length", 0) or 0, MAX_QUEUE_LENGTH)
        options = SubscribeOptions(fields.number("throttle_rate", 0.0), queue_length,
                                   fields.integer("fragment_size", 0) or 0, fields.compression())
        with self._lock:
            subscription = self.subscriptions.get(topic)
        if subscription is None:
            cls = self._topic_class(topic, fields.string("type", ""))
            subscription = ClientSubscription(topic, cls, self._send, self.shared.latest, self.shared.pacer)
            with self._lock:
                self.subscriptions[topic] = subscription
        elif fields.string("type", "") not in ("", subscription.message_class._type):
            raise protocol.ProtocolError(f"Tried to subscribe to {topic} as {fields.string('type')}, "
                                         f"but it is subscribed as {subscription.message_class._type}")
        subscription.add(fields.id, options)

    def _unsubscribe(self, fields: protocol.Fields) -> None:
        topic = self._topic(fields)
        with self._lock:
            subscription = self.subscriptions.get(topic)
            if subscription is None or not subscription.remove(fields.id):
                return
            del self.subscriptions[topic]
        subscription.close()

    # ------------------------------------------------------------------ services

    def _call_service(self, fields: protocol.Fields) -> None:
        service = self._service(fields)
        args = fields.op.get("args")
        fragment_size = fields.integer("fragment_size", 0) or 0
        compression = fields.compression()
        type_name = fields.string("type", "")
        op_id = fields.id

        with self._lock:
            if self._calls_in_progress >= MAX_CALLS_IN_PROGRESS:
                raise protocol.ProtocolError(f"call_service: {MAX_CALLS_IN_PROGRESS} calls of this client are "
                                             "already in progress", fields.name, op_id)
            self._calls_in_progress += 1

        def run() -> None:
            try:
                answer_call()
            except Exception as exc:  # the pool would keep it to itself: the client is told
                log.exception("call_service %s failed", service)
                self.status("error", f"call_service {service}: {exc}", op_id)
            finally:
                with self._lock:
                    self._calls_in_progress -= 1

        def answer_call() -> None:
            answer = call_service(self.shared.graph, service, type_name, args, op_id)
            text = protocol.encode_json(answer)
            if compression == "png":
                text = protocol.png_compress(text)
            for frame in protocol.fragments(text, fragment_size, str(op_id or f"call_service:{service}")):
                self.send_frame(frame)
            if not answer["result"]:
                self.status("error", f"call_service {service}: {answer['values']}", op_id)

        self.shared.workers.submit(run)

    def _advertise_service(self, fields: protocol.Fields) -> None:
        service = self._service(fields)
        type_name = fields.string("type")
        srv = service_class(type_name)
        if srv is None:
            raise protocol.ProtocolError(f"Unable to load the service class for type '{type_name}': no such type")
        with self.shared.lock:
            owner = self.shared.advertised_services.get(service)
            if owner is not None:
                if owner.session is not self:
                    raise protocol.ProtocolError(f"Service {service} is already advertised by another client")
                return
            advertised = AdvertisedService(self, service, srv, self._request_ids)
            self.shared.advertised_services[service] = advertised
        self.services[service] = advertised

    def _unadvertise_service(self, fields: protocol.Fields) -> None:
        service = self._service(fields)
        advertised = self.services.pop(service, None)
        if advertised is None:
            raise protocol.ProtocolError(f"Service {service} has not been advertised via rosbridge")
        self._drop_service(advertised)

    def _drop_service(self, advertised: AdvertisedService) -> None:
        with self.shared.lock:
            if self.shared.advertised_services.get(advertised.name) is advertised:
                del self.shared.advertised_services[advertised.name]
        advertised.close()

    def _service_response(self, fields: protocol.Fields) -> None:
        request_id = fields.op.get("id")
        named = fields.string("service", "")
        service = self.shared.graph.resolve(named) if named else ""
        for advertised in list(self.services.values()):
            if (not service or advertised.name == service) and advertised.answer(
                    request_id, fields.op.get("values"), fields.boolean("result", True)):
                return
        raise protocol.ProtocolError(f"service_response: no call {request_id!r} of {service} is waiting")

    # ------------------------------------------------------------------ the rest

    def _set_level(self, fields: protocol.Fields) -> None:
        level = fields.string("level")
        if level not in protocol.STATUS_LEVELS:
            raise protocol.ProtocolError(f"set_level: unknown level '{level}' (one of "
                                         f"{', '.join(protocol.STATUS_LEVELS)})", "set_level", fields.id)
        self.status_level = level

    def _fragment(self, fields: protocol.Fields) -> None:
        whole = self.defragmenter.add(fields.op)
        if whole is not None:
            self._dispatch(protocol.decode_frame(whole))

    def on_close(self) -> None:
        with self._lock:
            subscriptions, self.subscriptions = list(self.subscriptions.values()), {}
            publishers, self.publishers = list(self.publishers.values()), {}
        services, self.services = list(self.services.values()), {}
        for subscription in subscriptions:
            subscription.close()
        for publisher in publishers:
            publisher.unregister()
        for advertised in services:
            self._drop_service(advertised)
