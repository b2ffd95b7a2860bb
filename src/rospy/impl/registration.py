"""rospy.impl.registration: what this process's node has registered, and who hears of it.

- The process's RegistrationListeners (get_registration_listeners()) hear kame's Node itself:
  each publication, subscription and service the node registers with the master, or removes,
  calls the listeners' reg_added / reg_removed, as rospy's topic and service managers do.
- get_topic_manager() answers from the node's tables (`[[topic, type], ...]`) until
  set_topic_manager() puts another in its place; the service manager is rospy.service's.
- The process's listeners start with a registrar that tells the master, as the node, of what
  rospy code announces itself (ServiceManager.register, a topic manager of its own): rospy's
  RegManager does that for init_node's node. RegManager itself is a listener that tells the
  master of each registration it hears, through rospy.core.xmlrpcapi: kame's node registers its
  own topics and services, so init_node starts none; one made by a program registers what it is
  told of.
"""

from __future__ import annotations

import logging
import threading
from typing import Any

from kame.client import core
from kame.node.remote_poll import poll_remote
from rospy.core import (
    add_preshutdown_hook,
    get_caller_id,
    get_namespace,
    is_shutdown,
    is_shutdown_requested,
    logdebug,
    logerr,
    logfatal,
    loginfo,
    logwarn,
    signal_shutdown,
    xmlrpcapi,
)

__all__ = ["RegManager", "Registration", "RegistrationListener", "RegistrationListeners", "TopicManager",
           "add_preshutdown_hook", "get_caller_id", "get_namespace", "get_registration_listeners",
           "get_service_manager", "get_topic_manager", "is_shutdown", "is_shutdown_requested", "logdebug", "logerr",
           "logfatal", "loginfo", "logwarn", "set_service_manager", "set_topic_manager", "signal_shutdown",
           "xmlrpcapi"]

_REGISTER_RETRY = 0.2  # rospy's period between attempts to reach a master that is not up


class Registration:
    """Registration kinds."""

    PUB = "pub"
    SUB = "sub"
    SRV = "srv"


class RegistrationListener:
    """Told of each registration (a topic's type, or a service's URI) added or removed."""

    def reg_added(self, resolved_name: str, data_type_or_uri: str, reg_type: str) -> None:
        pass

    def reg_removed(self, resolved_name: str, data_type_or_uri: str, reg_type: str) -> None:
        pass


class RegistrationListeners:
    """A list of RegistrationListener, each told in turn (one's failure is logged, not raised)."""

    def __init__(self) -> None:
        self.listeners: list[RegistrationListener] = []
        self.lock = threading.Lock()

    def add_listener(self, listener: RegistrationListener) -> None:
        if not isinstance(listener, RegistrationListener):  # rospy asserts it
            raise AssertionError(f"not a RegistrationListener: {listener!r}")
        with self.lock:
            self.listeners.append(listener)

    def notify_removed(self, resolved_name: str, data_type_or_uri: str, reg_type: str) -> None:
        self._notify(False, resolved_name, data_type_or_uri, reg_type)

    def notify_added(self, resolved_name: str, data_type: str, reg_type: str) -> None:
        self._notify(True, resolved_name, data_type, reg_type)

    def _notify(self, added: bool, resolved_name: str, data_type_or_uri: str, reg_type: str,
                skip: RegistrationListener | None = None) -> None:
        with self.lock:
            listeners = [listener for listener in self.listeners if listener is not skip]
        for listener in listeners:
            try:
                if added:
                    listener.reg_added(resolved_name, data_type_or_uri, reg_type)
                else:
                    listener.reg_removed(resolved_name, data_type_or_uri, reg_type)
            except Exception:
                logging.getLogger("rospy.registration").exception("error notifying listener of %s",
                                                                  "registration" if added else "removal")

    def clear(self) -> None:
        with self.lock:
            del self.listeners[:]


_registration_listeners = RegistrationListeners()

_REGISTER = {Registration.PUB: "registerPublisher", Registration.SUB: "registerSubscriber",
             Registration.SRV: "registerService"}
_UNREGISTER = {Registration.PUB: "unregisterPublisher", Registration.SUB: "unregisterSubscriber",
               Registration.SRV: "unregisterService"}


def _owned(node: Any, resolved_name: str, reg_type: str) -> bool:
    tables = {Registration.PUB: node.publications, Registration.SUB: node.subscriptions,
              Registration.SRV: node.services}
    return resolved_name in tables.get(reg_type, {})


class _NodeRegistrar(RegistrationListener):
    """What rospy's RegManager does for the process: a registration that rospy code announces
    itself (a ServiceManager's register, a topic manager of its own) is told to the master as
    this node. It does not hear the node's own (_heard skips it): the node tells the master."""

    def reg_added(self, resolved_name: str, data_type_or_uri: str, reg_type: str) -> None:
        node = core.get_node()
        if node is not None and not _owned(node, resolved_name, reg_type):
            node.master.call(_REGISTER[reg_type], resolved_name, data_type_or_uri, node.uri)

    def reg_removed(self, resolved_name: str, data_type_or_uri: str, reg_type: str) -> None:
        node = core.get_node()
        if node is not None and not _owned(node, resolved_name, reg_type):
            node.master.call(_UNREGISTER[reg_type], resolved_name,
                             data_type_or_uri if reg_type == Registration.SRV else node.uri)


_registrar = _NodeRegistrar()
_registration_listeners.add_listener(_registrar)


def _heard(added: bool, resolved_name: str, type_or_uri: str, kind: str) -> None:
    _registration_listeners._notify(added, resolved_name, type_or_uri, kind, skip=_registrar)


core.defer_until_initialized(lambda node: node.on_registration.append(_heard))


def get_registration_listeners() -> RegistrationListeners:
    """The process's listeners: they hear what its node registers and removes."""
    return _registration_listeners


class TopicManager:
    """The node's publications and subscriptions (rospy.topics' _TopicManager)."""

    def __init__(self) -> None:
        self.lock = threading.RLock()

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

    def check_all(self) -> None:
        """Nothing to sweep: a kame connection leaves its topic's table as it ends."""

    def close_all(self) -> None:
        """Unregister and close every publication and subscription of the node."""
        node = core.get_node()
        if node is None:
            return
        for topic in self._table(Registration.PUB):
            node.unadvertise(topic)
        for topic in self._table(Registration.SUB):
            node.unsubscribe(topic)


_topic_manager: Any = TopicManager()
_service_manager: Any = None


def set_topic_manager(tm: Any) -> None:
    global _topic_manager
    _topic_manager = tm


def get_topic_manager() -> Any:
    return _topic_manager


def set_service_manager(sm: Any) -> None:
    global _service_manager
    _service_manager = sm


def get_service_manager() -> Any:
    """The process's service manager (rospy.service's ServiceManager unless one was set)."""
    if _service_manager is None:
        import rospy.service  # noqa: F401  (it sets its ServiceManager as the process's, as rospy's)
    return _service_manager


class RegManager(RegistrationListener):
    """rospy's registrar: registers with the master what the topic and service managers hold
    (start) and every registration it hears of afterwards, and removes them at shutdown."""

    def __init__(self, handler: Any) -> None:
        self.logger = logging.getLogger("rospy.registration")
        self.handler = handler
        self.uri: str | None = None
        self.master_uri: str | None = None
        self.registered = False
        self._stopped = threading.Event()
        add_preshutdown_hook(self.cleanup)

    def start(self, uri: str, master_uri: str) -> None:
        """Register the node at `uri` and all its managers hold with the master at `master_uri`
        (trying again while it is not up), then listen for more until shutdown or cleanup."""
        self.registered = False
        self.master_uri = master_uri
        self.uri = uri
        if master_uri and master_uri != uri:
            self.logger.info("Registering with master node %s", master_uri)
            if poll_remote(self._register_all, core.wait_for_shutdown, _REGISTER_RETRY) is None:
                return
        self.registered = True
        self.run()

    def _register_all(self) -> bool | None:
        master = xmlrpcapi(self.master_uri)
        tm, sm, caller_id = get_topic_manager(), get_service_manager(), get_caller_id()
        try:
            with tm.lock, sm.lock:
                for resolved_name, data_type in tm.get_publications():
                    self._check(master.registerPublisher(caller_id, resolved_name, data_type, self.uri),  # type: ignore[union-attr]
                                "publication topic", resolved_name)
                for resolved_name, data_type in tm.get_subscriptions():
                    answer = master.registerSubscriber(caller_id, resolved_name, data_type, self.uri)  # type: ignore[union-attr]
                    if self._check(answer, "subscription topic", resolved_name):
                        self.publisher_update(resolved_name, answer[2])
                for resolved_name, service_uri in sm.get_services():
                    self._check(master.registerService(caller_id, resolved_name, service_uri, self.uri),  # type: ignore[union-attr]
                                "service", resolved_name)
                get_registration_listeners().add_listener(self)
        except OSError:
            self.logger.error("Unable to immediately register with master node [%s]: master may not be running yet. "
                              "Will keep trying.", self.master_uri)
            return None
        return True

    @staticmethod
    def _check(answer: list[Any], what: str, resolved_name: str) -> bool:
        code, msg, _ = answer
        if code != 1:
            logfatal(f"cannot register {what} [{resolved_name}] with master: {msg}")
            signal_shutdown(f"master/node incompatibility with register {what}")
        return bool(code == 1)

    def is_registered(self) -> bool:
        return self.registered

    def run(self) -> None:
        """Wait until shutdown or cleanup (kame's node connects to the publishers it is told of)."""
        with core.woken_at_shutdown(self._stopped):
            self._stopped.wait()

    def cleanup(self, reason: str) -> None:
        """Unregister everything the managers hold from the master and close them."""
        self._stopped.set()
        master = xmlrpcapi(self.master_uri)
        if master is None:
            return
        get_registration_listeners().clear()
        tm, sm, caller_id = get_topic_manager(), get_service_manager(), get_caller_id()
        try:
            if tm is not None:
                for resolved_name, _ in tm.get_subscriptions():
                    master.unregisterSubscriber(caller_id, resolved_name, self.uri)
                for resolved_name, _ in tm.get_publications():
                    master.unregisterPublisher(caller_id, resolved_name, self.uri)
            if sm is not None:
                for resolved_name, service_uri in sm.get_services():
                    master.unregisterService(caller_id, resolved_name, service_uri)
        except Exception:
            self.logger.warning("unclean shutdown", exc_info=True)
        if tm is not None:
            tm.close_all()
        if sm is not None:
            sm.unregister_all()

    def reg_removed(self, resolved_name: str, data_type_or_uri: str, reg_type: str) -> None:
        master = xmlrpcapi(self.master_uri)
        if master is None:
            self.logger.error("Registrar: master_uri is not set yet, cannot inform master of deregistration")
            return
        try:
            if reg_type == Registration.PUB:
                master.unregisterPublisher(get_caller_id(), resolved_name, self.uri)
            elif reg_type == Registration.SUB:
                master.unregisterSubscriber(get_caller_id(), resolved_name, self.uri)
            elif reg_type == Registration.SRV:
                master.unregisterService(get_caller_id(), resolved_name, data_type_or_uri)
        except Exception:
            logwarn("unable to communicate with ROS Master, registrations are now out of sync")
            self.logger.error("unregistering %s failed", resolved_name, exc_info=True)

    def reg_added(self, resolved_name: str, data_type_or_uri: str, reg_type: str) -> None:
        master = xmlrpcapi(self.master_uri)
        if master is None:
            self.logger.error("Registrar: master_uri is not set yet, cannot inform master of registration")
            return
        method = {Registration.PUB: "registerPublisher", Registration.SUB: "registerSubscriber",
                  Registration.SRV: "registerService"}[reg_type]

        def register() -> bool | None:
            try:
                answer = getattr(master, method)(get_caller_id(), resolved_name, data_type_or_uri, self.uri)
            except OSError as exc:
                self.logger.error("%s\nUnable to register with master node [%s]: master may not be running yet. "
                                  "Will keep trying.", exc, self.master_uri)
                return None
            code, msg, val = answer
            if code != 1:
                logfatal(f"unable to register {reg_type} [{resolved_name}] with master: {msg}")
            elif reg_type == Registration.SUB:
                self.publisher_update(resolved_name, val)
            return True

        poll_remote(register, core.wait_for_shutdown, _REGISTER_RETRY)

    def publisher_update(self, resolved_name: str, uris: list[str]) -> None:
        """The publishers of `resolved_name` are `uris`: the node's subscription connects to them."""
        node = core.get_node()
        if node is not None:
            node.slave_call("publisherUpdate", ["/master", resolved_name, list(uris)])
