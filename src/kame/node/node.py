"""A ROS node: its name, its master, its XML-RPC ("slave") API and TCPROS server, and all it owns.

A Node is an explicit object: it owns its publications, subscriptions, services, threads
and sockets, and `shutdown()` unregisters from the master and ends every one of them.
Nothing here is process-wide; the rospy facade keeps the one node of a rospy program.

The slave API answers from the node's own tables (requestTopic, publisherUpdate,
paramUpdate, getBusInfo, getBusStats, getPid, shutdown, ...). Work a call starts that
could wait on the network (connecting to new publishers) runs on threads of its own.

Every thread the node starts is its own: `spawn` records it, and `shutdown()` closes what the
thread waits on (sockets, the reconnect back-off's event) and joins it, with a bounded wait,
so after shutdown no thread of the node is left running.
"""

from __future__ import annotations

import contextlib
import itertools
import logging
import os
import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, NamedTuple

from kame import names
from kame.arity import accepts
from kame.net.address import bind_host, uri_host
from kame.net.handshake import ClosedBeforeHeader, HandshakeError, MalformedHeader, read_header, write_header
from kame.net.rpc_server import RpcServer
from kame.net.stream import Flusher, Listener, peer_of, shut_down
from kame.net.workers import WorkerPool
from kame.node import local
from kame.node.master_proxy import MasterError, MasterProxy
from kame.node.master_watch import MasterWatch
from kame.node.publisher_link import PublisherLink
from kame.node.services import ServiceClient, ServiceHandler, ServiceServer
from kame.node.topics import (
    Callback,
    IncomingLink,
    MessagesCallback,
    Publication,
    SubscriberLink,
    Subscription,
)
from kame.node.unreachable import ReportedOnce
from kame.protocol import shmros, tcpros
from kame.protocol.xmlrpc import Fault, MalformedError, decode_request, encode_fault, encode_response

if TYPE_CHECKING:
    import socket

log = logging.getLogger("kame.node")

HANDSHAKE_TIMEOUT = 10.0
JOIN_TIMEOUT = 2.0  # how long shutdown waits, in all, for the node's threads to end


class NodeConfig(NamedTuple):
    name: str  # the full resolved node name, e.g. /ns/talker
    master_uri: str
    host: str  # the address advertised in our URIs
    bind_host: str = ""  # where our servers listen; '' means all interfaces
    remappings: tuple[tuple[str, str], ...] = ()
    xmlrpc_port: int = 0
    tcpros_port: int = 0


class Node:
    def __init__(self, config: NodeConfig) -> None:
        self.config = config
        self.name = config.name
        self.remappings = dict(config.remappings)
        self.master = MasterProxy(config.master_uri, config.name)
        self.is_shutdown = False
        self.shutdown_reason = ""
        self._ids = itertools.count(1)
        self._lock = threading.RLock()
        self.publications: dict[str, Publication] = {}
        self.subscriptions: dict[str, Subscription] = {}
        self.services: dict[str, ServiceServer] = {}
        self.param_cache: dict[str, Any] = {}
        self.params_set: dict[str, Any] = {}  # what this node set, for a restarted master
        # keys whose subscribeParam is on its way: the latest paramUpdate for each, if any came
        self._param_pending: dict[str, Any] = {}
        self.on_param_update: list[Callable[[str, Any], None]] = []
        # told (added, resolved name, type or service URI, "pub" | "sub" | "srv") of each registration
        # with the master and each removal: rospy's registration listeners hear them through it
        self.on_registration: list[Callable[[bool, str, str, str], None]] = []
        self.on_shutdown_request: Callable[[str], None] = self.shutdown
        # told the caller and message of a shutdown call before the shutdown starts (rospy prints them)
        self.on_shutdown_call: Callable[[str, str], None] | None = None
        self._shutdown_hooks: list[Callable[[str], None]] = []
        bind = config.bind_host or bind_host(config.host)
        self._threads: set[threading.Thread] = set()
        self._handshaking: set[socket.socket] = set()  # accepted sockets whose header is still to come
        self.flusher = Flusher(name="kame-flusher")
        self.workers = WorkerPool("kame-handshake")
        self._bad_attempts = _Throttled(log)
        self.unreachable_reported = ReportedOnce()  # publishers whose address we said we cannot use
        self.listener = Listener(bind, config.tcpros_port, self._accept, name="kame-tcpros")
        self.rpc = RpcServer(bind, config.xmlrpc_port, self._rpc, name="kame-xmlrpc")
        self.uri = f"http://{uri_host(config.host)}:{self.rpc.port}/"
        self.tcpros_port = self.listener.port
        self.rpc.start()
        self.master_watch = MasterWatch(config.master_uri, config.name, self._has_registrations,
                                        self.register_again)
        self.spawn(self.master_watch.run, "kame-master-watch")

    # ------------------------------------------------------------------ utilities

    def next_connection_id(self) -> int:
        return next(self._ids)

    def publisher_link(self, subscription: Subscription, uri: str) -> IncomingLink:
        """A new link of `subscription` to the publisher at `uri`: straight to our own
        publication when the publisher is this node (kame.node.local), else a PublisherLink
        (TCPROS, or shared memory with a kame publisher on this host)."""
        if uri == self.uri and local.enabled():
            return local.LocalPublisherLink(subscription, uri, self.next_connection_id())
        return PublisherLink(subscription, uri, self.next_connection_id())

    def spawn(self, target: Callable[[], None], name: str) -> threading.Thread:
        """Run `target` on a thread the node owns: shutdown() joins it. The target must end
        once the node shuts down (it waits on sockets or events that shutdown closes or sets)."""
        thread = threading.Thread(target=target, name=name, daemon=True)
        with self._lock:
            self._threads = {t for t in self._threads if t.is_alive()}
            self._threads.add(thread)
            thread.start()  # under the lock: shutdown never sees a thread that has not started
        return thread

    def resolve(self, name: str) -> str:
        return names.resolve(name, self.name, self.remappings)

    def add_shutdown_hook(self, hook: Callable[[str], None]) -> None:
        self._shutdown_hooks.append(hook)

    def _registration_changed(self, added: bool, name: str, type_or_uri: str, kind: str) -> None:
        for listener in list(self.on_registration):
            try:
                listener(added, name, type_or_uri, kind)
            except Exception:
                log.exception("registration listener %s failed", listener)

    # ------------------------------------------------------------------ topics

    def advertise(self, topic: str, type: str, md5sum: str, definition: str, latch: bool = False,
                  queue_size: int = 0, headers: dict[str, str] | None = None,
                  on_connect: Callable[[SubscriberLink], None] | None = None,
                  on_disconnect: Callable[[SubscriberLink], None] | None = None,
                  tcp_nodelay: bool = False) -> Publication:
        """Publish `topic` (already resolved); registers with the master at once. `headers` are
        extra fields for the connection header subscribers receive. `on_connect`/`on_disconnect`
        are in place before registering, so no early subscriber is missed. `tcp_nodelay` is for
        subscribers that do not ask for it either way in their header (as rospy's)."""
        with self._lock:
            pub = self.publications.get(topic)
            new = pub is None
            if pub is None:
                pub = Publication(self, topic, type, md5sum, definition, latch, queue_size, dict(headers or {}),
                                  tcp_nodelay)
                self.publications[topic] = pub
            else:
                pub.latch = pub.latch or latch
                pub.queue_size = max(pub.queue_size, queue_size)
                pub.tcp_nodelay = pub.tcp_nodelay or tcp_nodelay
            if on_connect is not None:
                pub.on_connect.append(on_connect)
            if on_disconnect is not None:
                pub.on_disconnect.append(on_disconnect)
        self.master.call("registerPublisher", topic, type, self.uri)
        if new:
            self._registration_changed(True, topic, type, "pub")
        return pub

    def unadvertise(self, topic: str) -> None:
        with self._lock:
            pub = self.publications.pop(topic, None)
        if pub is None:
            return
        pub.close()
        self._best_effort("unregisterPublisher", topic, self.uri)
        self._registration_changed(False, topic, pub.type, "pub")

    def subscribe(self, topic: str, type: str, md5sum: str, definition: str, deliver: Callback,
                  queue_size: int | None = None, tcp_nodelay: bool = False,
                  buff_size: int | None = None, max_frame: int | None = None, message_class: type[Any] | None = None,
                  deliver_messages: MessagesCallback | None = None, shared_memory: bool = True,
                  read_interval: float = 0.0) -> Subscription:
        """Subscribe to `topic` (already resolved); see Subscription for tcp_nodelay, buff_size
        and read_interval. `max_frame`: the largest message accepted (default: the type's size
        when it has no variable-length fields, else 1 GiB); a larger one drops that publisher's
        connection. `deliver_messages` gets messages of `message_class` that a publication of this
        node publishes as objects, unserialized (kame.node.local); `shared_memory=False` is the
        transport hint that keeps this subscription off shared memory (kame.protocol.shmros)."""
        with self._lock:
            if topic in self.subscriptions:
                raise ValueError(f"already subscribed to {topic}")
            sub = Subscription(self, topic, type, md5sum, definition, queue_size, tcp_nodelay, deliver, buff_size,
                               max_frame, message_class, deliver_messages, shared_memory, read_interval)
            self.subscriptions[topic] = sub
        publishers = self.master.call("registerSubscriber", topic, type, self.uri)
        sub.registered([str(uri) for uri in publishers], updates_before=0)
        self._registration_changed(True, topic, type, "sub")
        return sub

    def unsubscribe(self, topic: str) -> None:
        with self._lock:
            sub = self.subscriptions.pop(topic, None)
        if sub is None:
            return
        sub.close()
        self._best_effort("unregisterSubscriber", topic, self.uri)
        self._registration_changed(False, topic, sub.type, "sub")

    # ------------------------------------------------------------------ services

    def advertise_service(self, name: str, type: str, md5sum: str, handler: ServiceHandler) -> ServiceServer:
        with self._lock:
            if name in self.services:
                raise ValueError(f"service [{name}] already registered")
            server = ServiceServer(name, type, md5sum, handler)
            self.services[name] = server
        self.master.call("registerService", name, self.service_uri, self.uri)
        self._registration_changed(True, name, self.service_uri, "srv")
        return server

    def unadvertise_service(self, name: str) -> None:
        with self._lock:
            server = self.services.pop(name, None)
        if server is None:
            return
        server.close()
        self._best_effort("unregisterService", name, self.service_uri)
        self._registration_changed(False, name, self.service_uri, "srv")

    @property
    def service_uri(self) -> str:
        return f"rosrpc://{uri_host(self.config.host)}:{self.tcpros_port}"

    def service_client(self, name: str, type: str, md5sum: str, persistent: bool = False,
                       headers: dict[str, str] | None = None) -> ServiceClient:
        return ServiceClient(self.master, self.name, name, type, md5sum, persistent, headers)

    # ------------------------------------------------------------------ TCPROS server

    def _accept(self, sock: socket.socket, addr: Any) -> None:
        self.workers.submit(lambda: self._handshake(sock))

    def _handshake(self, sock: socket.socket) -> None:
        with self._lock:
            if self.is_shutdown:
                sock.close()
                return
            self._handshaking.add(sock)
        try:
            header = read_header(sock, HANDSHAKE_TIMEOUT)
            sock.settimeout(None)
        except ClosedBeforeHeader:
            sock.close()
            return
        except MalformedHeader as exc:
            self._bad_attempts.warning("bad TCPROS connection attempt from %s: %s", peer_of(sock), exc)
            with contextlib.suppress(OSError):  # tell the peer why, as for any refused connection
                write_header(sock, tcpros.error_header_fields(str(exc)))
            sock.close()
            return
        except (OSError, HandshakeError) as exc:
            if not self.is_shutdown:
                self._bad_attempts.warning("bad TCPROS connection attempt from %s: %s", peer_of(sock), exc)
            sock.close()
            return
        finally:
            with self._lock:
                self._handshaking.discard(sock)
        kind = tcpros.classify_connection(header)
        try:
            if kind == "topic":
                error = self.connect_subscriber(sock, header)
            elif kind == "service":
                error = self.connect_service_client(sock, header)
            else:
                error = kind.error
            if error is not None:
                self._refuse(sock, error, header)
        except (OSError, KeyError) as exc:
            log.debug("connection ended during the handshake: %s", exc)
            sock.close()
        except Exception:
            # the worker pool would swallow it, leaving the socket open and nothing in the log
            log.exception("TCPROS connection from %s for %s failed", header.get("callerid", "?"),
                          header.get("topic") or header.get("service") or "?")
            sock.close()

    def connect_subscriber(self, sock: socket.socket, header: dict[str, str]) -> str | None:
        """Serve the subscriber whose connection header `header` came on `sock` from our publication;
        the reason it is refused, or None once the publication owns `sock`."""
        with self._lock:
            specs = {topic: pub.spec for topic, pub in self.publications.items()}
        accepted = tcpros.accept_subscriber(header, callerid=self.name, publications=specs)
        if isinstance(accepted, tcpros.Rejected):
            return accepted.error
        pub = self.publications.get(accepted.topic)
        if pub is None:
            return f"[{self.name}] is not a publisher of [{accepted.topic}]"
        use_shm = False
        if shmros.HEADER_FIELD in header:  # a kame subscriber's offer: nobody else loads kame.net.shm
            from kame.net import shm

            use_shm = shmros.accept(header, shm.local_token())
        pub.attach(sock, accepted, use_shm)
        return None

    def connect_service_client(self, sock: socket.socket, header: dict[str, str]) -> str | None:
        """Serve the service client whose connection header `header` came on `sock`; the reason it is
        refused, or None once the service owns `sock`."""
        with self._lock:
            service_specs = {name: server.spec for name, server in self.services.items()}
        service_ok = tcpros.accept_service_client(header, callerid=self.name, services=service_specs)
        if isinstance(service_ok, tcpros.Rejected):
            return service_ok.error
        self.services[service_ok.service].attach(sock, service_ok)
        return None

    def _refuse(self, sock: socket.socket, text: str, header: dict[str, str]) -> None:
        log.error("refusing connection from %s: %s", header.get("callerid", "?"), text)
        try:
            write_header(sock, tcpros.error_header_fields(text))
        except OSError:
            pass
        sock.close()

    # ------------------------------------------------------------------ slave XML-RPC API

    def _rpc(self, body: bytes) -> bytes:
        try:
            method, params = decode_request(body)
        except (MalformedError, Fault) as exc:
            return encode_fault(1, f"<class 'Exception'>:malformed request: {exc}")
        answer = self.slave_call(method, params)
        if answer is None:
            return encode_fault(1, f"<class 'Exception'>:method \"{method}\" is not supported")
        return encode_response(answer)

    def slave_call(self, method: str, params: list[Any]) -> list[Any] | None:
        """The slave API's answer to `method` with `params` (caller_id first), checked as
        rospy checks them; None for a method the API does not have."""
        handler = _SLAVE_METHODS.get(method)
        if handler is None:
            return None
        if not params:
            return [-1, "missing required caller_id parameter", 0]
        if not isinstance(params[0], str):
            return [-1, "caller_id must be a string", 0]
        invalid = _invalid_param(method, params)
        if invalid is not None:
            log.warning("slave API %s from [%s] refused: %s", method, params[0], invalid)
            return [-1, invalid, _ERROR_VALUE.get(method, 0)]
        if not accepts(handler, 1 + len(params)):
            return [-1, "Error: bad call arity", 0]
        try:
            return handler(self, *params)
        except Exception as exc:
            log.exception("slave API %s failed", method)
            return [0, f"internal failure: {exc}", 0]

    def _get_bus_info(self, caller_id: str) -> list[Any]:
        info: list[Any] = []
        for topic, pub in list(self.publications.items()):
            for link in pub.links:
                info.append([link.connection_id, link.callerid, "o", link.transport, topic, True, link.peer])
        for topic, sub in list(self.subscriptions.items()):
            for uri, plink in list(sub.links.items()):
                info.append([plink.connection_id, uri, "i", plink.transport, topic, plink.connected, plink.callerid])
        return [1, "bus info", info]

    def _get_bus_stats(self, caller_id: str) -> list[Any]:
        """rospy's rows: a publication's connections [id, bytes, messages, connected] with the
        messages its queue dropped after them (kame's; readers of four fields are unaffected), a
        subscription's [id, bytes, messages, drops, connected], drops in roscpp's place for them."""
        pubs = [[t, p.bytes_sent, [[lk.connection_id, lk.sender.bytes_sent, lk.sender.frames_sent, True,
                                    lk.sender.dropped] for lk in p.links]]
                for t, p in list(self.publications.items())]
        subs = [[t, [[lk.connection_id, lk.bytes_received, lk.messages_received, lk.dropped, lk.connected]
                     for lk in s.links.values()]]
                for t, s in list(self.subscriptions.items())]
        return [1, "", [pubs, subs, [0, 0, 0]]]

    def _request_topic(self, caller_id: str, topic: str, protocols: list[Any]) -> list[Any]:
        if topic not in self.publications:
            return [-1, f"Not a publisher of [{topic}]", []]
        for protocol in protocols:
            if isinstance(protocol, list) and protocol and protocol[0] == "TCPROS":
                return [1, f"ready on {self.config.host}:{self.tcpros_port}",
                        ["TCPROS", self.config.host, self.tcpros_port]]
        return [0, "no supported protocol implementations", []]

    def set_param(self, key: str, value: Any) -> None:
        """setParam, remembered so that a restarted master gets it again (`key` resolved)."""
        self.master.call("setParam", key, value)
        with self._lock:
            self.params_set = {k: v for k, v in self.params_set.items()
                               if not (k == key or k.startswith(key.rstrip("/") + "/"))}
            self.params_set[key] = value

    def delete_param(self, key: str) -> None:
        self.master.call("deleteParam", key)
        with self._lock:
            self.params_set = {k: v for k, v in self.params_set.items()
                               if not (k == key or k.startswith(key.rstrip("/") + "/"))}

    def _has_registrations(self) -> bool:
        return bool(self.publications or self.subscriptions or self.services)

    def register_again(self) -> None:
        """Everything this node has told the master, told again (a restarted master knows nothing)."""
        with self._lock:
            params = list(self.params_set.items())
            watched = list(self.param_cache)
            services = list(self.services)
            publications = [(p.topic, p.type) for p in self.publications.values()]
            subscriptions = [(s.topic, s.type) for s in self.subscriptions.values()]
        for key, value in params:
            self.master.call("setParam", key, value)
        for key in watched:
            self.master.call("subscribeParam", self.uri, key)
        for name in services:
            self.master.call("registerService", name, self.service_uri, self.uri)
        for topic, type in publications:
            self.master.call("registerPublisher", topic, type, self.uri)
        for topic, type in subscriptions:
            sub = self.subscriptions.get(topic)
            updates = sub.updates if sub is not None else 0
            publishers = self.master.call("registerSubscriber", topic, type, self.uri)
            if sub is not None:
                sub.registered([str(uri) for uri in publishers], updates)

    def _publisher_update(self, caller_id: str, topic: str, publishers: list[Any]) -> list[Any]:
        sub = self.subscriptions.get(topic)
        if sub is not None:
            sub.publisher_update([str(uri) for uri in publishers])
        return [1, "", 0]

    def cached_param(self, key: str) -> Any:
        """`key`'s value from the parameter cache, subscribing (subscribeParam) on first use.
        A paramUpdate that arrives while subscribeParam is on its way is newer than what it
        returns, and is what gets cached."""
        with self._lock:
            if key in self.param_cache:
                return self.param_cache[key]
            self._param_pending.setdefault(key, _NO_UPDATE)
        try:
            value = self.master.call("subscribeParam", self.uri, key)
        except BaseException:
            with self._lock:
                self._param_pending.pop(key, None)
            raise
        with self._lock:
            newer = self._param_pending.pop(key, _NO_UPDATE)
            if key in self.param_cache:  # a concurrent first use stored it; updates went there since
                return self.param_cache[key]
            if newer is not _NO_UPDATE:
                value = newer
            self.param_cache[key] = value
        return value

    def _param_update(self, caller_id: str, key: str, value: Any) -> list[Any]:
        key = names.canonicalize(key) or "/"
        matched = False
        with self._lock:
            for store in (self.param_cache, self._param_pending):
                for cached in list(store):
                    if cached == key or cached.startswith(key.rstrip("/") + "/"):
                        matched = True
                        if cached == key:
                            store[cached] = value
                        else:
                            store[cached] = _subvalue(value, cached[len(key.rstrip("/")) + 1:])
        for callback in self.on_param_update:
            callback(key, value)
        if not matched:
            return [-1, "not subscribed", 0]
        return [1, "", 0]

    def _shutdown_call(self, caller_id: str, msg: str = "") -> list[Any]:
        reason = f"external shutdown request from [{caller_id}]: {msg}"
        log.info("shutdown request: %s", reason)
        if self.on_shutdown_call is not None:
            self.on_shutdown_call(caller_id, msg)
        self.spawn(lambda: self.on_shutdown_request(reason), "kame-shutdown")
        return [1, "shutdown", 0]

    # ------------------------------------------------------------------ shutdown

    def _best_effort(self, method: str, *args: Any) -> None:
        try:
            self.master.call(method, *args, timeout=1.0)
        except (OSError, MasterError) as exc:
            log.debug("%s failed during shutdown: %s", method, exc)

    def shutdown(self, reason: str = "") -> None:
        """Unregister from the master and end every connection, server and thread we own."""
        with self._lock:
            if self.is_shutdown:
                return
            self.is_shutdown = True
            self.shutdown_reason = reason
        self.master_watch.close()
        for hook in list(self._shutdown_hooks):
            try:
                hook(reason)
            except Exception:
                log.exception("shutdown hook failed")
        for topic in list(self.publications):
            self.unadvertise(topic)
        for topic in list(self.subscriptions):
            self.unsubscribe(topic)
        for name in list(self.services):
            self.unadvertise_service(name)
        for key in list(self.param_cache):
            self._best_effort("unsubscribeParam", self.uri, key)
        deadline = time.monotonic() + JOIN_TIMEOUT
        self.listener.close()
        with self._lock:
            handshaking = list(self._handshaking)
        for sock in handshaking:  # wakes the workers reading their headers
            shut_down(sock)
        self.workers.close(timeout=_left(deadline))
        self.rpc.close(timeout=_left(deadline))
        self.flusher.close()
        self.master.close()
        with self._lock:
            threads = [t for t in self._threads if t is not threading.current_thread()]
        for thread in threads:
            thread.join(_left(deadline))
        stuck = [t.name for t in threads if t.is_alive()]
        if stuck:
            log.warning("threads still running %.1f s after shutdown began: %s", JOIN_TIMEOUT, ", ".join(stuck))


_NO_UPDATE = object()  # no paramUpdate came while subscribeParam was on its way


class _Throttled:
    """Warnings about other peers' bad attempts, at most one per `interval`: a flood of garbage
    connections gives a line a second with a count, not a line per connection."""

    def __init__(self, logger: logging.Logger, interval: float = 1.0) -> None:
        self._log = logger
        self._interval = interval
        self._lock = threading.Lock()
        self._last = -interval
        self._suppressed = 0

    def warning(self, fmt: str, *args: object) -> None:
        now = time.monotonic()
        with self._lock:
            if now - self._last < self._interval:
                self._suppressed += 1
                return
            self._last = now
            suppressed, self._suppressed = self._suppressed, 0
        if suppressed:
            self._log.warning(fmt + " (and %d more like it in the last second, not shown)", *args, suppressed)
        else:
            self._log.warning(fmt, *args)


def _left(deadline: float) -> float:
    return max(0.0, deadline - time.monotonic())


def _subvalue(value: Any, path: str) -> Any:
    for part in [p for p in path.split("/") if p]:
        if not isinstance(value, dict) or part not in value:
            return {}
        value = value[part]
    return value


# rospy's argument validators (rospy.impl.masterslave / validators), with their texts: a bad
# value is refused with -1 before it can touch the node's state (a publisherUpdate whose list
# is not a list of URLs must not drop the publishers we have).


def _check_topic(name: str, value: Any) -> str | None:
    if not value or not isinstance(value, str):
        return f"ERROR: parameter [{name}] must be a non-empty string"
    if ":" in value or " " in value:
        return f"ERROR: parameter [{name}] contains illegal chars"
    return None


def _check_non_empty_list(name: str, value: Any) -> str | None:
    if not value or not isinstance(value, list):
        return f"ERROR: parameter [{name}] must be specified and non-empty"
    return None


def _check_non_empty_str(name: str, value: Any) -> str | None:
    if not value or not isinstance(value, str):
        return f"ERROR: parameter [{name}] must be a non-empty string"
    return None


def _check_publishers(name: str, value: Any) -> str | None:
    if not isinstance(value, list):
        return f"ERROR: param [{name}] must be a list"
    for uri in value:
        if not isinstance(uri, str):
            return f"ERROR: param [{name}] must be a list of strings"
        scheme, sep, rest = uri.partition("://")
        if not sep or not scheme or not rest.split("/", 1)[0]:
            return f"ERROR: param [{name}] does not contain valid URLs [{uri}]"
    return None


_PARAM_CHECKS: dict[str, tuple[tuple[str, Callable[[str, Any], str | None]], ...]] = {
    "requestTopic": (("topic", _check_topic), ("protocols", _check_non_empty_list)),
    "publisherUpdate": (("topic", _check_topic), ("publishers", _check_publishers)),
    "paramUpdate": (("parameter_key", _check_non_empty_str),),
}
_ERROR_VALUE: dict[str, Any] = {"requestTopic": []}


def _invalid_param(method: str, params: list[Any]) -> str | None:
    """rospy's text for the first invalid argument after caller_id, or None (arity is checked
    when the handler is called)."""
    for (name, check), value in zip(_PARAM_CHECKS.get(method, ()), params[1:], strict=False):
        error = check(name, value)
        if error is not None:
            return error
    return None


_SLAVE_METHODS: dict[str, Callable[..., list[Any]]] = {
    "getBusStats": Node._get_bus_stats,
    "getBusInfo": Node._get_bus_info,
    "getMasterUri": lambda node, caller_id: [1, node.config.master_uri, node.config.master_uri],
    "getUri": lambda node, caller_id: [1, "", node.uri],
    "getName": lambda node, caller_id: [1, "", node.name],
    "getPid": lambda node, caller_id: [1, "", os.getpid()],
    "getSubscriptions": lambda node, caller_id: [1, "subscriptions",
                                                 [[t, s.type] for t, s in list(node.subscriptions.items())]],
    "getPublications": lambda node, caller_id: [1, "publications",
                                                [[t, p.type] for t, p in list(node.publications.items())]],
    "requestTopic": Node._request_topic,
    "publisherUpdate": Node._publisher_update,
    "paramUpdate": Node._param_update,
    "shutdown": Node._shutdown_call,
}
