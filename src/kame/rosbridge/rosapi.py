"""rosapi's node: the graph, types and parameters as ROS services, for web clients.

`rosrun rosapi rosapi_node` (rosbridge_websocket.launch starts it as /rosapi). Its services are
rosapi's (the rosapi package's srv types): /rosapi/topics, topic_type, services, nodes,
get_param, set_param, ... as roslibjs calls them. Parameter values travel as JSON text both
ways, as rosapi's: get_param answers json.dumps of the value (its `default`, JSON text too, when
the parameter is not set), set_param takes JSON text (plain text when it is not JSON).
~topics_glob, ~services_glob and ~params_glob limit what it lists and touches.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Callable, Sequence
from typing import Any

from kame.client import core
from kame.client.clock import get_rostime
from kame.client.process import (
    delete_param,
    get_param,
    get_param_names,
    has_param,
    init_node,
    search_param,
    set_param,
    spin,
)
from kame.client.services import Service, ServiceException
from kame.msg.lookup import message_class, service_class
from kame.rosbridge import globs
from kame.rosbridge.graph import Graph
from kame.rosbridge.typedefs import typedefs
from rosapi import msg as rosapi_msg
from rosapi import srv

ACTION_TOPICS = ("goal", "cancel", "status", "feedback", "result")


class RosApi:
    def __init__(self, graph: Graph, topics_glob: tuple[str, ...] | None, services_glob: tuple[str, ...] | None,
                 params_glob: tuple[str, ...] | None) -> None:
        self.graph = graph
        self.topics_glob, self.services_glob, self.params_glob = topics_glob, services_glob, params_glob
        handlers: dict[str, tuple[Any, Callable[[Any], Any]]] = {
            "topics": (srv.Topics, self.topics), "topics_for_type": (srv.TopicsForType, self.topics_for_type),
            "topics_and_raw_types": (srv.TopicsAndRawTypes, self.topics_and_raw_types),
            "services": (srv.Services, self.services),
            "services_for_type": (srv.ServicesForType, self.services_for_type),
            "nodes": (srv.Nodes, self.nodes), "node_details": (srv.NodeDetails, self.node_details),
            "action_servers": (srv.GetActionServers, self.action_servers),
            "topic_type": (srv.TopicType, self.topic_type), "service_type": (srv.ServiceType, self.service_type),
            "publishers": (srv.Publishers, self.publishers), "subscribers": (srv.Subscribers, self.subscribers),
            "service_providers": (srv.ServiceProviders, self.service_providers),
            "service_node": (srv.ServiceNode, self.service_node), "service_host": (srv.ServiceHost, self.service_host),
            "message_details": (srv.MessageDetails, self.message_details),
            "service_request_details": (srv.ServiceRequestDetails, self.service_request_details),
            "service_response_details": (srv.ServiceResponseDetails, self.service_response_details),
            "set_param": (srv.SetParam, self.set_param), "get_param": (srv.GetParam, self.get_param),
            "has_param": (srv.HasParam, self.has_param), "search_param": (srv.SearchParam, self.search_param),
            "delete_param": (srv.DeleteParam, self.delete_param),
            "get_param_names": (srv.GetParamNames, self.get_param_names), "get_time": (srv.GetTime, self.get_time),
        }
        self.servers = [Service(f"~{name}", cls, handler) for name, (cls, handler) in handlers.items()]

    # ------------------------------------------------------------------ topics

    def _topic_types(self) -> list[tuple[str, str]]:
        return sorted((t, ty) for t, ty in self.graph.topic_types() if globs.allows(self.topics_glob, t))

    def topics(self, request: Any) -> Any:
        pairs = self._topic_types()
        return srv.TopicsResponse([t for t, _ in pairs], [ty for _, ty in pairs])

    def topics_for_type(self, request: Any) -> Any:
        return srv.TopicsForTypeResponse([t for t, ty in self._topic_types() if ty == request.type])

    def topics_and_raw_types(self, request: Any) -> Any:
        pairs = self._topic_types()
        texts = []
        for _, type_name in pairs:
            cls = message_class(type_name)
            texts.append(cls._full_text if cls is not None else "")
        return srv.TopicsAndRawTypesResponse([t for t, _ in pairs], [ty for _, ty in pairs], texts)

    def topic_type(self, request: Any) -> Any:
        topic = request.topic
        return srv.TopicTypeResponse(self.graph.topic_type(topic) if globs.allows(self.topics_glob, topic) else "")

    def _nodes_of(self, entries: list[Any], name: str) -> list[str]:
        return sorted(next((list(nodes) for n, nodes in entries if n == name), []))

    def publishers(self, request: Any) -> Any:
        return srv.PublishersResponse(self._nodes_of(self.graph.system_state()[0], request.topic))

    def subscribers(self, request: Any) -> Any:
        return srv.SubscribersResponse(self._nodes_of(self.graph.system_state()[1], request.topic))

    def action_servers(self, request: Any) -> Any:
        topics = {t for t, _ in self._topic_types()}
        found = sorted({t[: -len("/goal")] for t in topics if t.endswith("/goal")
                        and all(f"{t[: -len('/goal')]}/{suffix}" in topics for suffix in ACTION_TOPICS)})
        return srv.GetActionServersResponse(found)

    # ------------------------------------------------------------------ services and nodes

    def _services(self) -> list[str]:
        return sorted(name for name, _ in self.graph.system_state()[2] if globs.allows(self.services_glob, name))

    def services(self, request: Any) -> Any:
        return srv.ServicesResponse(self._services())

    def services_for_type(self, request: Any) -> Any:
        return srv.ServicesForTypeResponse([s for s in self._services() if self.graph.service_type(s) == request.type])

    def service_type(self, request: Any) -> Any:
        service = request.service
        allowed = globs.allows(self.services_glob, service)
        return srv.ServiceTypeResponse(self.graph.service_type(service) if allowed else "")

    def service_providers(self, request: Any) -> Any:
        return srv.ServiceProvidersResponse(self._nodes_of(self.graph.system_state()[2], request.service))

    def service_node(self, request: Any) -> Any:
        providers = self._nodes_of(self.graph.system_state()[2], request.service)
        return srv.ServiceNodeResponse(providers[0] if providers else "")

    def service_host(self, request: Any) -> Any:
        return srv.ServiceHostResponse(self.graph.service_host(request.service))

    def nodes(self, request: Any) -> Any:
        found: set[str] = set()
        for entries in self.graph.system_state():
            for _, nodes in entries:
                found.update(nodes)
        return srv.NodesResponse(sorted(found))

    def node_details(self, request: Any) -> Any:
        publishers, subscribers, services = self.graph.system_state()

        def of(entries: list[Any]) -> list[str]:
            return sorted(name for name, nodes in entries if request.node in nodes)

        return srv.NodeDetailsResponse(of(subscribers), of(publishers), of(services))

    # ------------------------------------------------------------------ types

    def _details(self, cls: Any, type_name: str) -> list[Any]:
        if cls is None:
            raise ServiceException(f"no such type: {type_name}")
        return [rosapi_msg.TypeDef(t.type, list(t.fieldnames), list(t.fieldtypes), list(t.fieldarraylen),
                                   list(t.examples), list(t.constnames), list(t.constvalues)) for t in typedefs(cls)]

    def message_details(self, request: Any) -> Any:
        return srv.MessageDetailsResponse(self._details(message_class(request.type), request.type))

    def service_request_details(self, request: Any) -> Any:
        service = service_class(request.type)
        cls = service._request_class if service is not None else None
        return srv.ServiceRequestDetailsResponse(self._details(cls, request.type))

    def service_response_details(self, request: Any) -> Any:
        service = service_class(request.type)
        cls = service._response_class if service is not None else None
        return srv.ServiceResponseDetailsResponse(self._details(cls, request.type))

    # ------------------------------------------------------------------ parameters

    def _param(self, name: str) -> str:
        resolved = core.resolve_name(name)
        if not globs.allows(self.params_glob, resolved):
            raise ServiceException(f"parameter {resolved} is not allowed (params_glob)")
        return resolved

    def get_param(self, request: Any) -> Any:
        default: Any = None
        if request.default != "":
            try:
                default = json.loads(request.default)
            except ValueError:
                default = request.default
        return srv.GetParamResponse(json.dumps(get_param(self._param(request.name), default)))

    def set_param(self, request: Any) -> Any:
        try:
            value = json.loads(request.value)
        except ValueError:
            value = request.value
        set_param(self._param(request.name), value)
        return srv.SetParamResponse()

    def has_param(self, request: Any) -> Any:
        return srv.HasParamResponse(has_param(self._param(request.name)))

    def search_param(self, request: Any) -> Any:
        return srv.SearchParamResponse(search_param(request.name) or "")

    def delete_param(self, request: Any) -> Any:
        name = self._param(request.name)
        if has_param(name):
            delete_param(name)
        return srv.DeleteParamResponse()

    def get_param_names(self, request: Any) -> Any:
        return srv.GetParamNamesResponse(sorted(n for n in get_param_names() if globs.allows(self.params_glob, n)))

    def get_time(self, request: Any) -> Any:
        return srv.GetTimeResponse(get_rostime())


def main(argv: Sequence[str] | None = None) -> int:
    init_node("rosapi", list(sys.argv if argv is None else argv))
    RosApi(Graph(), globs.parse(get_param("~topics_glob", None)), globs.parse(get_param("~services_glob", None)),
           globs.parse(get_param("~params_glob", None)))
    spin()
    return 0
