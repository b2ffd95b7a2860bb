"""foxglove_bridge on kame: ROS 1 topics, services, parameters, the graph and time for Foxglove's
WebSocket clients (`roslaunch foxglove_bridge foxglove_bridge.launch`, port 8765).

- Topics: a channel per published topic (kame.foxglove_bridge.graph), its schema the full ros1msg
  definition. A subscription is one raw subscription of the bridge's node per topic (type "*",
  as rosbag record), shared by all the clients that subscribe; each message's TCPROS bytes go
  to every subscribed client as they came, behind the 13 bytes of ws-protocol's header.
- Client publish: a client's channel of a type kame knows becomes a publication of the bridge's
  node; each message is checked against its type before it is published.
- Services, parameters and the connection graph go through the master and the services'
  TCPROS, on the bridge's own threads: the WebSocket thread never waits on ROS.
- Every client's send buffer is bounded by ~send_buffer_limit (kame.net.websocket_hub): a slow
  client misses messages, and only its own. A frame that is not ws-protocol, an unknown op, a
  wrong type or a type that does not exist gets a status message back; the others go on.
- Time: under /use_sim_time, every /clock message is broadcast (capability "time").
"""

from __future__ import annotations

import contextlib
import functools
import logging
import queue
import threading
import time
import uuid
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from kame import names
from kame.foxglove_bridge import protocol as wsp
from kame.foxglove_bridge.graph import Offer, SystemState, allowed, compile_whitelist
from kame.msg.errors import MessageError
from kame.msg.lookup import message_class, service_class
from kame.net.websocket_hub import HubClient, WebSocketHub
from kame.net.workers import WorkerPool
from kame.node.master_proxy import MasterError
from kame.node.node import Node
from kame.node.services import ServiceClient, ServiceError, probe_service
from kame.node.topics import Publication

log = logging.getLogger("kame.foxglove_bridge")

SERVICE_PROBE_TIMEOUT = 0.25  # seconds: Noetic's service_type_retrieval_timeout_ms
SERVICE_CALL_TIMEOUT = 30.0
MAX_PENDING = 64  # a client's requests waiting on ROS at once, its service calls included


@dataclass(frozen=True)
class BridgeConfig:
    address: str = "0.0.0.0"
    port: int = 8765
    topic_whitelist: tuple[str, ...] = (".*",)
    param_whitelist: tuple[str, ...] = (".*",)
    service_whitelist: tuple[str, ...] = (".*",)
    client_topic_whitelist: tuple[str, ...] = (".*",)
    capabilities: tuple[str, ...] = ("clientPublish", "parameters", "parametersSubscribe", "services",
                                     "connectionGraph")
    max_update_ms: int = 5000
    send_buffer_limit: int = 10_000_000
    use_sim_time: bool = False


def schema_of(type_name: str) -> str | None:
    try:
        cls = message_class(type_name)
    except MessageError:
        return None
    return None if cls is None else str(cls._full_text)


def _service_schemas(type_name: str) -> tuple[str, str, str] | None:
    try:
        cls = service_class(type_name)
    except MessageError:
        return None
    if cls is None:
        return None
    return str(cls._md5sum), str(cls._request_class._full_text), str(cls._response_class._full_text)


@dataclass
class _Session:
    client: HubClient
    subscriptions: dict[int, int] = field(default_factory=dict)  # subscription id -> channel id
    advertised: dict[int, tuple[wsp.ClientChannel, Any]] = field(default_factory=dict)  # with its class
    parameters: set[str] = field(default_factory=set)
    graph: bool = False
    pending: int = 0  # requests handed to the bridge's threads and not yet done


@dataclass
class _ClientPublication:
    publication: Publication
    cls: Any
    users: int = 0


class FoxgloveBridge:
    def __init__(self, node: Node, config: BridgeConfig, now_ns: Callable[[], int]) -> None:
        self.node = node
        self.config = config
        self._now_ns = now_ns
        topics, bad_topics = compile_whitelist(config.topic_whitelist)
        services, bad_services = compile_whitelist(config.service_whitelist)
        self._params, bad_params = compile_whitelist(config.param_whitelist)
        self._client_topics, bad_client = compile_whitelist(config.client_topic_whitelist)
        for pattern in bad_topics + bad_services + bad_params + bad_client:
            log.error("Failed to parse whitelist pattern [%s]", pattern)
        self.offer = Offer(topics, services, schema_of)
        self.capabilities = [c for c in config.capabilities if c in wsp.CAPABILITIES and c != "time"]
        if config.use_sim_time:
            self.capabilities.append("time")
        self._session_id = uuid.uuid4().hex
        self._lock = threading.RLock()
        self._sessions: dict[int, _Session] = {}
        self._subscribers: dict[int, dict[int, int]] = {}  # channel id -> client id -> subscription id
        self._topic_of: dict[int, str] = {}  # channel id -> topic the node subscribes for it
        self._publications: dict[str, _ClientPublication] = {}
        self._param_subscribed: set[str] = set()
        self._state: SystemState | None = None
        self._jobs: queue.SimpleQueue[Callable[[], None] | None] = queue.SimpleQueue()
        self._calls = WorkerPool("kame-foxglove-call")
        self._stop = threading.Event()
        self.hub = WebSocketHub(config.address, config.port, wsp.SUBPROTOCOL, self, "foxglove_bridge",
                                config.send_buffer_limit, config.send_buffer_limit)
        node.on_param_update.append(self._param_updated)
        self._worker = node.spawn(self._work, "kame-foxglove-bridge")
        node.add_shutdown_hook(lambda reason: self.close())  # before the node joins its threads

    # ------------------------------------------------------------------ the bridge's own thread

    def _work(self) -> None:
        """Runs the graph updates every max_update_ms (the master sends no event for new topics)
        and, in order, what clients asked for that waits on ROS."""
        period = max(self.config.max_update_ms, 100) / 1000.0
        deadline = 0.0
        while not self._stop.is_set():
            try:
                job = self._jobs.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                job = self._update_graph
            if job is None:
                return
            try:
                job()
            except (OSError, MasterError) as exc:
                log.warning("foxglove_bridge: the master could not be asked: %s", exc)
            except Exception:  # one request's failure must not end the thread every client relies on
                log.exception("foxglove_bridge: a request failed")
            if job == self._update_graph:
                deadline = time.monotonic() + period

    def _later(self, job: Callable[[], None]) -> None:
        self._jobs.put(job)

    def _update_graph(self) -> None:
        state = SystemState.from_master(self.node.master.call("getSystemState"),
                                        self.node.master.call("getTopicTypes"))
        described: dict[str, wsp.ServiceInfo | None] = {}
        for name in self.offer.services_to_describe(state):
            described[name] = self._describe_service(name)
        with self._lock:
            self._state = state
            channels, unknown = self.offer.update_channels(state)
            services = self.offer.update_services(state, described)
            graph = self.offer.graph_update(state)
            sessions = list(self._sessions.values())
            for channel_id in channels.removed:
                self._drop_channel(channel_id)
        for type_name in unknown:
            log.warning("foxglove_bridge: no definition of [%s] here: its topics are not offered", type_name)
        for session in sessions:
            if channels.removed:
                session.client.send_control(wsp.unadvertise(channels.removed))
            if channels.added:
                session.client.send_control(wsp.advertise(channels.added))
            if "services" in self.capabilities:
                if services.removed:
                    session.client.send_control(wsp.unadvertise_services(services.removed))
                if services.added:
                    session.client.send_control(wsp.advertise_services(services.added))
            if graph is not None and session.graph:
                session.client.send_control(wsp.connection_graph_update(*graph))

    def _describe_service(self, name: str) -> wsp.ServiceInfo | None:
        try:
            header = probe_service(self.node.master, self.node.name, name, SERVICE_PROBE_TIMEOUT)
        except (OSError, MasterError, ValueError) as exc:
            log.debug("service [%s] could not be asked its type: %s", name, exc)
            return None
        type_name = header.get("type", "")
        schemas = _service_schemas(type_name)
        if schemas is None:
            return None
        return wsp.ServiceInfo(0, name, type_name, schemas[1], schemas[2])

    # ------------------------------------------------------------------ the hub's events (its thread)

    def opened(self, client: HubClient) -> None:
        with self._lock:
            self._sessions[client.id] = _Session(client)
            channels = list(self.offer.channels.values())
            services = list(self.offer.services.values())
        log.info("foxglove_bridge: client %s connected", client.peer)
        client.send_control(wsp.server_info("foxglove_bridge", self.capabilities, self._session_id,
                                            self.config.use_sim_time))
        if channels:
            client.send_control(wsp.advertise(channels))
        if services and "services" in self.capabilities:
            client.send_control(wsp.advertise_services(services))
        self._later(self._update_graph)

    def closed(self, client: HubClient) -> None:
        with self._lock:
            session = self._sessions.pop(client.id, None)
        if session is None:
            return
        log.info("foxglove_bridge: client %s disconnected (%d messages dropped at its send buffer limit)",
                 client.peer, client.dropped)
        self._later(lambda: self._forget(session))

    def _forget(self, session: _Session) -> None:
        with self._lock:
            for channel_id in list(session.subscriptions.values()):
                self._unsubscribe_channel(session.client.id, channel_id)
            for channel, _ in session.advertised.values():
                self._release_publication(channel.topic)

    def received(self, client: HubClient, message: str | bytes) -> None:
        with self._lock:
            session = self._sessions.get(client.id)
        if session is None:
            return
        try:
            request = wsp.parse_text(message) if isinstance(message, str) else wsp.parse_binary(message)
            self._dispatch(session, request)
        except wsp.ProtocolError as exc:
            client.send_control(wsp.status(wsp.ERROR, str(exc)))

    def _need(self, capability: str) -> None:
        if capability not in self.capabilities:
            raise wsp.ProtocolError(f"the server does not have the capability '{capability}'")

    def _counted(self, session: _Session, job: Callable[[], None]) -> Callable[[], None]:
        """`job`, counted against the client's MAX_PENDING: a client cannot make the bridge hold an
        unbounded backlog of its requests (or threads for its service calls)."""
        with self._lock:
            if session.pending >= MAX_PENDING:
                raise wsp.ProtocolError(f"too many requests waiting (at most {MAX_PENDING}): this one was dropped")
            session.pending += 1

        def run() -> None:
            try:
                job()
            finally:
                with self._lock:
                    session.pending -= 1

        return run

    def _dispatch(self, session: _Session, request: wsp.Request) -> None:
        if isinstance(request, wsp.Subscribe):
            self._later(self._counted(session, lambda: self._subscribe(session, request)))
        elif isinstance(request, wsp.Unsubscribe):
            self._later(self._counted(session, lambda: self._unsubscribe(session, request)))
        elif isinstance(request, (wsp.ClientAdvertise, wsp.ClientUnadvertise, wsp.ClientMessageData)):
            self._need("clientPublish")
            self._client_publish(session, request)
        elif isinstance(request, (wsp.GetParameters, wsp.SetParameters)):
            self._need("parameters")
            self._later(self._counted(session, lambda: self._parameters(session, request)))
        elif isinstance(request, wsp.ParameterUpdates):
            self._need("parametersSubscribe")
            self._later(self._counted(session, lambda: self._parameter_updates(session, request)))
        elif isinstance(request, wsp.ConnectionGraphUpdates):
            self._need("connectionGraph")
            self._later(self._counted(session, lambda: self._graph_updates(session, request.subscribe)))
        else:
            assert isinstance(request, wsp.ServiceCallRequest)
            self._need("services")
            try:
                call = self._counted(session, lambda: self._call_service(session, request))
            except wsp.ProtocolError as exc:
                session.client.send_control(wsp.service_call_failure(request.service_id, request.call_id, str(exc)))
                return
            self._calls.submit(call)

    # ------------------------------------------------------------------ topics to clients

    def _subscribe(self, session: _Session, request: wsp.Subscribe) -> None:
        client = session.client
        for subscription_id, channel_id in request.subscriptions:
            with self._lock:
                channel = self.offer.channel(channel_id)
                if channel is None:
                    client.send_control(wsp.status(wsp.ERROR, f"no channel {channel_id}"))
                    continue
                if subscription_id in session.subscriptions:
                    client.send_control(wsp.status(wsp.ERROR, f"subscription {subscription_id} is already in use"))
                    continue
                if channel_id in session.subscriptions.values():
                    client.send_control(wsp.status(wsp.WARNING, f"already subscribed to channel {channel_id}"))
                    continue
                session.subscriptions[subscription_id] = channel_id
                subscribers = self._subscribers.setdefault(channel_id, {})
                subscribers[client.id] = subscription_id
                first = channel_id not in self._topic_of
                if first:
                    self._topic_of[channel_id] = channel.topic
            if first:
                self._subscribe_topic(channel_id, channel.topic)

    def _subscribe_topic(self, channel_id: int, topic: str) -> None:
        def deliver(frames: list[memoryview], header: dict[str, str]) -> None:
            self._forward(channel_id, frames)

        try:
            self.node.subscribe(topic, "*", "*", "", deliver, queue_size=10)
            log.info("foxglove_bridge: subscribed to [%s] for channel %d", topic, channel_id)
        except ValueError as exc:  # the node already subscribes to it (another channel of the topic)
            log.warning("foxglove_bridge: cannot subscribe to [%s]: %s", topic, exc)

    def _forward(self, channel_id: int, frames: list[memoryview]) -> None:
        with self._lock:
            targets = [(self._sessions[c].client, s) for c, s in self._subscribers.get(channel_id, {}).items()
                       if c in self._sessions]
        if not targets:
            return
        stamp = self._now_ns()
        for frame in frames:
            for client, subscription_id in targets:
                client.send_data(b"".join((wsp.message_data_header(subscription_id, stamp), frame)))

    def _unsubscribe(self, session: _Session, request: wsp.Unsubscribe) -> None:
        with self._lock:
            for subscription_id in request.subscription_ids:
                channel_id = session.subscriptions.pop(subscription_id, None)
                if channel_id is None:
                    session.client.send_control(wsp.status(wsp.WARNING, f"no subscription {subscription_id}"))
                    continue
                self._unsubscribe_channel(session.client.id, channel_id)

    def _unsubscribe_channel(self, client_id: int, channel_id: int) -> None:
        subscribers = self._subscribers.get(channel_id, {})
        subscribers.pop(client_id, None)
        if not subscribers:
            self._drop_channel(channel_id)

    def _drop_channel(self, channel_id: int) -> None:
        self._subscribers.pop(channel_id, None)
        topic = self._topic_of.pop(channel_id, None)
        if topic is not None:
            self.node.unsubscribe(topic)

    def broadcast_time(self, stamp_ns: int) -> None:
        """Tell every client the time (the "time" capability: /clock's, under /use_sim_time)."""
        message = wsp.time_message(stamp_ns)
        with self._lock:
            clients = [s.client for s in self._sessions.values()]
        for client in clients:
            client.send_data(message)

    # ------------------------------------------------------------------ clients' topics

    def _client_publish(self, session: _Session, request: wsp.Request) -> None:
        client = session.client
        if isinstance(request, wsp.ClientMessageData):
            advertised = session.advertised.get(request.channel_id)
            if advertised is None:
                raise wsp.ProtocolError(f"client channel {request.channel_id} is not advertised")
            channel, cls = advertised
            try:
                cls().deserialize(request.data)
            except Exception as exc:  # any failure to read it means the bytes are not this type
                raise wsp.ProtocolError(f"a message on {channel.topic} is not a valid {channel.schema_name}: "
                                        f"{type(exc).__name__}") from None
            with self._lock:
                target = self._publications.get(channel.topic)
            if target is not None and target.cls is cls:
                target.publication.publish_payload(request.data)
            else:  # the advertisement is still on its way to the master: publish after it
                self._later(self._counted(session, functools.partial(self._publish, channel.topic, cls,
                                                                     request.data)))
            return
        if isinstance(request, wsp.ClientUnadvertise):
            for channel_id in request.channel_ids:
                gone = session.advertised.pop(channel_id, None)
                if gone is None:
                    raise wsp.ProtocolError(f"client channel {channel_id} is not advertised")
                self._later(functools.partial(self._release_publication, gone[0].topic))
            return
        assert isinstance(request, wsp.ClientAdvertise)
        for channel in request.channels:
            if channel.encoding != wsp.ROS1_ENCODING:
                raise wsp.ProtocolError(f"unsupported encoding '{channel.encoding}': only 'ros1' is")
            if channel.id in session.advertised:
                raise wsp.ProtocolError(f"client channel {channel.id} is already advertised")
            topic = names.canonicalize(channel.topic)
            if not names.is_global(topic) or not names.is_legal_name(topic) or topic == "/" \
                    or not allowed(topic, self._client_topics):
                raise wsp.ProtocolError(f"the topic '{channel.topic}' may not be published")
            try:
                cls = message_class(channel.schema_name)
            except MessageError:
                cls = None
            if cls is None:
                raise wsp.ProtocolError(f"unknown message type '{channel.schema_name}'")
            session.advertised[channel.id] = (wsp.ClientChannel(channel.id, topic, channel.encoding,
                                                                channel.schema_name), cls)
            self._later(self._counted(session, functools.partial(self._take_publication, client, topic, cls)))

    def _take_publication(self, client: HubClient, topic: str, cls: Any) -> None:
        with self._lock:
            held = self._publications.get(topic)
            if held is not None and held.cls is not cls:
                client.send_control(wsp.status(wsp.ERROR, f"{topic} is already published as {held.cls._type}"))
                return
            if held is None:
                publication = self.node.advertise(topic, cls._type, cls._md5sum, cls._full_text, queue_size=10)
                held = self._publications[topic] = _ClientPublication(publication, cls)
            held.users += 1

    def _publish(self, topic: str, cls: Any, data: bytes) -> None:
        with self._lock:
            target = self._publications.get(topic)
        if target is not None and target.cls is cls:
            target.publication.publish_payload(data)

    def _release_publication(self, topic: str) -> None:
        with self._lock:
            held = self._publications.get(topic)
            if held is None:
                return
            held.users -= 1
            if held.users <= 0:
                del self._publications[topic]
                self.node.unadvertise(topic)

    # ------------------------------------------------------------------ services

    def _call_service(self, session: _Session, request: wsp.ServiceCallRequest) -> None:
        client = session.client
        with self._lock:
            service = self.offer.service(request.service_id)
        if service is None:
            client.send_control(wsp.service_call_failure(request.service_id, request.call_id,
                                                         f"no service {request.service_id}"))
            return
        if request.encoding != wsp.ROS1_ENCODING:
            client.send_control(wsp.service_call_failure(request.service_id, request.call_id,
                                                         f"unsupported encoding '{request.encoding}'"))
            return
        schemas = _service_schemas(service.type)
        if schemas is None:
            client.send_control(wsp.service_call_failure(request.service_id, request.call_id,
                                                         f"unknown service type '{service.type}'"))
            return
        caller = ServiceClient(self.node.master, self.node.name, service.name, service.type, schemas[0], False)
        try:
            response = caller.call(request.data, timeout=SERVICE_CALL_TIMEOUT)
        except (ServiceError, OSError, MasterError) as exc:
            client.send_control(wsp.service_call_failure(request.service_id, request.call_id, str(exc)))
            return
        client.send_control(wsp.service_call_response(request.service_id, request.call_id, wsp.ROS1_ENCODING,
                                                      response))

    # ------------------------------------------------------------------ parameters

    def _param_allowed(self, name: str) -> bool:
        return allowed(name, self._params)

    def _get(self, name: str) -> Any:
        try:
            return self.node.master.call("getParam", name)
        except MasterError:
            return None

    def _parameters(self, session: _Session, request: wsp.GetParameters | wsp.SetParameters) -> None:
        if isinstance(request, wsp.SetParameters):
            for name, value in request.parameters:
                if not self._param_allowed(name):
                    session.client.send_control(wsp.status(wsp.WARNING, f"parameter '{name}' may not be set"))
                    continue
                if value is None:
                    with contextlib.suppress(MasterError):
                        self.node.master.call("deleteParam", name)
                else:
                    self.node.master.call("setParam", name, value)
            wanted: tuple[str, ...] = tuple(name for name, _ in request.parameters)
            if request.request_id is None:
                return
        else:
            wanted = request.names or tuple(self.node.master.call("getParamNames"))
        found = [(n, self._get(n)) for n in wanted if self._param_allowed(n)]
        session.client.send_control(wsp.parameter_values([(n, v) for n, v in found if v is not None],
                                                         request.request_id))

    def _parameter_updates(self, session: _Session, request: wsp.ParameterUpdates) -> None:
        names_ = [n for n in request.names if self._param_allowed(n)]
        with self._lock:
            if request.subscribe:
                session.parameters.update(names_)
                new = [n for n in names_ if n not in self._param_subscribed]
                self._param_subscribed.update(new)
            else:
                session.parameters.difference_update(names_)
                new = []
        for name in new:
            self.node.master.call("subscribeParam", self.node.uri, name)

    def _param_updated(self, key: str, value: Any) -> None:
        with self._lock:
            sessions = list(self._sessions.values())
        for session in sessions:
            touched = [n for n in session.parameters if n == key or n.startswith(key.rstrip("/") + "/")]
            if touched:
                self._later(functools.partial(self._send_parameters, session, touched))

    def _send_parameters(self, session: _Session, wanted: list[str]) -> None:
        found = [(n, self._get(n)) for n in wanted]
        session.client.send_control(wsp.parameter_values([(n, v) for n, v in found if v is not None], None))

    # ------------------------------------------------------------------ the connection graph

    def _graph_updates(self, session: _Session, subscribe: bool) -> None:
        with self._lock:
            session.graph = subscribe
            state = self._state
        if subscribe and state is not None:
            session.client.send_control(wsp.connection_graph_update(state.publishers, state.subscribers,
                                                                    state.services, [], []))

    def close(self) -> None:
        """Stop serving: the clients are disconnected, the bridge's threads end (again: nothing)."""
        self._stop.set()
        self._jobs.put(None)
        self.hub.close()
        self._calls.close()
        self._worker.join(2.0)

