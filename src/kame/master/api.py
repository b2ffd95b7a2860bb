"""The Master and Parameter Server XML-RPC APIs as a pure function: (method, params) -> result.

Rules (ros1-interop spec §2-4; rosmaster 1.15.15 master_api.py):
- Every method takes caller_id first and answers `[code, message, value]`; when code is not 1
  the value is the method's placeholder (`0`, `''`, `[]`, ...).
- Argument checks run in rosmaster's order: no params, then arity, then caller_id's type, then
  each argument's validator, which also resolves names against caller_id. A TypeError inside a
  method is the caller's fault (-1), anything else an internal failure (0).
- Unknown (and `_private`) methods are an XML-RPC fault 1, as Python's SimpleXMLRPCServer gives;
  system.multicall answers a list of one-element lists or fault structs.
- A paramUpdate answered with -1 does not unsubscribe the node: rosmaster 1.15.15 means to, but
  fails with an internal error, so nodes already live with unwanted updates (quirk 21).
Nothing here waits or does I/O: changes come back as notifications for the server to send, and a
shutdown request as a flag.
"""

from __future__ import annotations

import traceback
from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

from kame import names
from kame.master.notifications import Notification
from kame.master.param_tree import ParamTree, param_updates, subscription_key, unstorable
from kame.master.registry import Registry
from kame.protocol.xmlrpc import Fault, Value

Reply = tuple[int, str, object]


class CallResult(NamedTuple):
    """What one XML-RPC call produced (a NamedTuple: a frozen dataclass costs a microsecond more per call)."""

    value: object  # the response value (for ROS methods the [code, message, value] triple)
    notifications: tuple[Notification, ...] = ()
    shutdown: str | None = None  # set when the caller asked the master to stop: its message
    failure: str | None = None  # traceback of an internal failure, for the log


class _Invalid(Exception):
    """An argument failed its check; the message goes back to the caller as is."""


# ------------------------------------------------------------------------------ validators
# Each takes (value, caller_id) and returns the value to use (names come back resolved).

Validator = Callable[[Value, str], Value]


def _non_empty_str(param: str) -> Validator:
    def check(v: Value, _caller: str) -> Value:
        if not v:
            raise _Invalid(f"ERROR: parameter [{param}] must be specified and non-empty")
        if not isinstance(v, str):
            raise _Invalid(f"ERROR: parameter [{param}] must be a string")
        return v

    return check


def _any(v: Value, _caller: str) -> Value:
    return v


def _api(param: str) -> Validator:
    def check(v: Value, _caller: str) -> Value:
        if not v or not isinstance(v, str):
            raise _Invalid(f"ERROR: parameter [{param}] is not an XMLRPC URI")
        if not v.startswith(("http://", "rosrpc://")):
            raise _Invalid(f"ERROR: parameter [{param}] is not an RPC URI")
        return v

    return check


def _name(param: str) -> Validator:
    def check(v: Value, caller: str) -> Value:
        if not v or not isinstance(v, str):
            raise _Invalid(f"ERROR: parameter [{param}] must be a non-empty string")
        if ":" in v or " " in v:
            raise _Invalid(f"ERROR: parameter [{param}] contains illegal chars")
        if v[0] == "/" and v[-1] != "/" and "//" not in v:
            return v  # already global and canonical, as clients send most names: resolves to itself
        return names.resolve(v, caller)

    return check


def _graph_name(param: str) -> Validator:
    """A topic or service: a name that is not the global namespace itself.

    The check is on the text as sent, so `//` slips through and resolves to `/`, as in rosmaster.
    """
    resolve = _name(param)

    def check(v: Value, caller: str) -> Value:
        resolved = resolve(v, caller)
        if v == names.GLOBAL_NS:
            raise _Invalid(f"ERROR: parameter [{param}] cannot be the global namespace")
        return resolved

    return check


def _empty_or_name(param: str) -> Validator:
    def check(v: Value, caller: str) -> Value:
        if not isinstance(v, str):
            raise _Invalid(f"ERROR: parameter [{param}] must be a string")
        return names.resolve(v, caller) if v else ""

    return check


def _type_name(param: str) -> Validator:
    def check(v: Value, _caller: str) -> Value:
        if v == names.ANY_TYPE:
            return v
        if not v or not isinstance(v, str):
            raise _Invalid(f"ERROR: parameter [{param}] must be a non-empty string")
        if v.count("/") != 1:
            raise _Invalid(f"ERROR: parameter [{param}] is not a valid package resource name")
        return v

    return check


_KEY = _non_empty_str("key")
_TOPIC = _graph_name("topic")
_SERVICE = _graph_name("service")
_CALLER_API = _api("caller_api")


@dataclass(frozen=True)
class _Method:
    impl: Callable[..., Reply]
    default: object  # the value placed in error replies
    validators: tuple[Validator, ...]


class MasterApi:
    """The state of one master and the methods that read and change it.

    Public methods named in camelCase are the XML-RPC methods, under their wire names.
    """

    def __init__(self, uri: str, pid: int) -> None:
        self.uri = uri
        self.pid = pid
        self.registry = Registry()
        self.params = ParamTree()
        self._outbox: list[Notification] = []
        self._shutdown: str | None = None
        self._failure: str | None = None
        self._methods: dict[str, _Method] = {
            "getUri": _Method(self.getUri, "", ()),
            "getPid": _Method(self.getPid, -1, ()),
            "shutdown": _Method(self.shutdown, 0, (_any,)),
            "deleteParam": _Method(self.deleteParam, 0, (_KEY,)),
            "setParam": _Method(self.setParam, 0, (_KEY, _any)),
            "getParam": _Method(self.getParam, 0, (_KEY,)),
            "searchParam": _Method(self.searchParam, 0, (_KEY,)),
            "subscribeParam": _Method(self.subscribeParam, 0, (_CALLER_API, _KEY)),
            "unsubscribeParam": _Method(self.unsubscribeParam, 0, (_CALLER_API, _KEY)),
            "hasParam": _Method(self.hasParam, False, (_KEY,)),
            "getParamNames": _Method(self.getParamNames, [], ()),
            "registerService": _Method(self.registerService, 0, (_SERVICE, _api("service_api"), _CALLER_API)),
            "lookupService": _Method(self.lookupService, "", (_SERVICE,)),
            "unregisterService": _Method(self.unregisterService, 0, (_SERVICE, _api("service_api"))),
            "registerSubscriber": _Method(
                self.registerSubscriber, [], (_TOPIC, _type_name("topic_type"), _CALLER_API)),
            "unregisterSubscriber": _Method(self.unregisterSubscriber, 0, (_TOPIC, _CALLER_API)),
            "registerPublisher": _Method(
                self.registerPublisher, [], (_TOPIC, _type_name("topic_type"), _CALLER_API)),
            "unregisterPublisher": _Method(self.unregisterPublisher, 0, (_TOPIC, _CALLER_API)),
            "lookupNode": _Method(self.lookupNode, "", (_name("node"),)),
            "getPublishedTopics": _Method(self.getPublishedTopics, 0, (_empty_or_name("subgraph"),)),
            "getTopicTypes": _Method(self.getTopicTypes, [], ()),
            "getSystemState": _Method(self.getSystemState, [[], [], []], ()),
        }

    # ---------------------------------------------------------------------------- dispatch

    def call(self, method: str, params: list[Value]) -> CallResult:
        """Serve one XML-RPC call. Raises Fault for methods a Python ROS server does not have."""
        self._outbox = []
        self._shutdown = None
        self._failure = None
        value = self._dispatch(method, params)
        return CallResult(value, tuple(self._outbox), self._shutdown, self._failure)

    def _dispatch(self, method: str, params: list[Value]) -> object:
        if method == "system.multicall":
            return self._multicall(params)
        m = self._methods.get(method)
        if m is None:
            raise Fault(1, f"<class 'Exception'>:method \"{method}\" is not supported")
        return list(self._checked(m, params))

    def _multicall(self, params: list[Value]) -> object:
        if len(params) != 1 or not isinstance(params[0], list):
            raise Fault(1, "<class 'TypeError'>:system.multicall takes one array of calls")
        results: list[object] = []
        for call in params[0]:
            method = call.get("methodName") if isinstance(call, dict) else None
            if not isinstance(method, str):
                raise Fault(1, "<class 'KeyError'>:'methodName'")
            sub_params = call.get("params")  # type: ignore[union-attr]
            if not isinstance(sub_params, list):
                raise Fault(1, "<class 'KeyError'>:'params'")
            try:
                results.append([self._dispatch(method, sub_params)])
            except Fault as f:
                results.append({"faultCode": f.code, "faultString": f.message})
        return results

    def _checked(self, m: _Method, params: list[Value]) -> Reply:
        if not params:
            return -1, "missing required caller_id parameter", m.default
        if len(params) != len(m.validators) + 1:
            return -1, "Error: bad call arity", m.default
        caller_id = params[0]
        if not isinstance(caller_id, str):
            return -1, "caller_id must be a string", m.default
        try:
            args = [check(v, caller_id) for check, v in zip(m.validators, params[1:], strict=True)]
        except _Invalid as e:
            return -1, str(e), m.default
        try:
            return m.impl(caller_id, *args)
        except TypeError as e:
            self._failure = traceback.format_exc()
            return -1, f"Error: invalid arguments: {e}", m.default
        except Exception as e:
            self._failure = traceback.format_exc()
            return 0, f"Internal failure: {e}", m.default

    # ---------------------------------------------------------------------------- master

    def getUri(self, caller_id: str) -> Reply:
        return 1, "", self.uri

    def getPid(self, caller_id: str) -> Reply:
        return 1, "", self.pid

    def shutdown(self, caller_id: str, msg: str) -> Reply:
        self._shutdown = f"external shutdown request from [{caller_id}]: {msg}"
        return 1, "shutdown", 0

    # ---------------------------------------------------------------------------- parameters

    def deleteParam(self, caller_id: str, key: str) -> Reply:
        key = names.resolve(key, caller_id)
        try:
            self.params.delete(key)
        except KeyError:
            return -1, f"parameter [{key}] is not set", 0
        self._outbox.extend(param_updates(self.registry.param_subscribers, key, {}))
        return 1, f"parameter {key} deleted", 0

    def setParam(self, caller_id: str, key: str, value: Value) -> Reply:
        key = names.resolve(key, caller_id)
        problem = unstorable(key, value)
        if problem:
            return -1, problem, 0
        self.params.set(key, value)
        self._outbox.extend(param_updates(self.registry.param_subscribers, key, value, caller_id))
        return 1, f"parameter {key} set", 0

    def getParam(self, caller_id: str, key: str) -> Reply:
        key = names.resolve(key, caller_id)
        try:
            return 1, f"Parameter [{key}]", self.params.get(key)
        except KeyError:
            return -1, f"Parameter [{key}] is not set", 0

    def searchParam(self, caller_id: str, key: str) -> Reply:
        found = self.params.search(caller_id, key)
        if found:
            return 1, f"Found [{found}]", found
        return -1, f"Cannot find parameter [{key}] in an upwards search", ""

    def subscribeParam(self, caller_id: str, caller_api: str, key: str) -> Reply:
        key = names.resolve(key, caller_id)
        try:
            value = self.params.get(key)
        except KeyError:
            value = {}
        notes = self.registry.register_param_subscriber(subscription_key(key), caller_id, caller_api)
        self._outbox.extend(notes)
        return 1, f"Subscribed to parameter [{key}]", value

    def unsubscribeParam(self, caller_id: str, caller_api: str, key: str) -> Reply:
        key = names.resolve(key, caller_id)
        self.registry.unregister_param_subscriber(subscription_key(key), caller_id, caller_api)
        return 1, f"Unsubscribe to parameter [{key}]", 1

    def hasParam(self, caller_id: str, key: str) -> Reply:
        key = names.resolve(key, caller_id)
        return 1, key, self.params.has(key)

    def getParamNames(self, caller_id: str) -> Reply:
        return 1, "Parameter names", self.params.names()

    # ---------------------------------------------------------------------------- registration

    def registerService(self, caller_id: str, service: str, service_api: str, caller_api: str) -> Reply:
        self._outbox.extend(self.registry.register_service(service, service_api, caller_id, caller_api))
        return 1, f"Registered [{caller_id}] as provider of [{service}]", 1

    def lookupService(self, caller_id: str, service: str) -> Reply:
        api = self.registry.lookup_service(service)
        if api:
            return 1, f"rosrpc URI: [{api}]", api
        return -1, "no provider", ""

    def unregisterService(self, caller_id: str, service: str, service_api: str) -> Reply:
        return self.registry.unregister_service(service, service_api, caller_id)

    def registerSubscriber(self, caller_id: str, topic: str, topic_type: str, caller_api: str) -> Reply:
        publishers, notes = self.registry.register_subscriber(topic, topic_type, caller_id, caller_api)
        self._outbox.extend(notes)
        return 1, f"Subscribed to [{topic}]", publishers

    def unregisterSubscriber(self, caller_id: str, topic: str, caller_api: str) -> Reply:
        return self.registry.unregister_subscriber(topic, caller_id, caller_api)

    def registerPublisher(self, caller_id: str, topic: str, topic_type: str, caller_api: str) -> Reply:
        subscribers, notes = self.registry.register_publisher(topic, topic_type, caller_id, caller_api)
        self._outbox.extend(notes)
        return 1, f"Registered [{caller_id}] as publisher of [{topic}]", subscribers

    def unregisterPublisher(self, caller_id: str, topic: str, caller_api: str) -> Reply:
        status, notes = self.registry.unregister_publisher(topic, caller_id, caller_api)
        self._outbox.extend(notes)
        return status

    # ---------------------------------------------------------------------------- introspection

    def lookupNode(self, caller_id: str, node: str) -> Reply:
        api = self.registry.lookup_node(node)
        if api is not None:
            return 1, "node api", api
        return -1, f"unknown node [{node}]", ""

    def getPublishedTopics(self, caller_id: str, subgraph: str) -> Reply:
        if subgraph and not subgraph.endswith(names.SEP):
            subgraph += names.SEP
        return 1, "current topics", self.registry.published_topics(subgraph)

    def getTopicTypes(self, caller_id: str) -> Reply:
        return 1, "current system state", self.registry.topic_types()

    def getSystemState(self, caller_id: str) -> Reply:
        return 1, "current system state", self.registry.system_state()
