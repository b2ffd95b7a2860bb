"""rqt_graph's model: what the master and the nodes said, turned into the graph to draw (pure).

Rules, as rqt_graph (and rosgraph.impl.graph) build their dot graph:
- A snapshot holds the master's registrations (getSystemState) and the live connections each
  node reported (getBusInfo, only those marked connected), named publisher -> subscriber.
  A node whose getBusInfo failed or did not answer in time is `unreachable`.
- "Nodes only": one oval per node, an edge per live connection labelled with its topic.
  "Nodes/Topics (active)": topics with a live connection become boxes, with edges
  publisher -> topic -> subscriber from the connections. "Nodes/Topics (all)": every
  registered topic, edges from the registrations.
- Hide debug drops nodes and topics whose name contains one of rqt_graph's QUIET_NAMES (a
  substring test, as rqt_graph does: `/rosout` also hides `/rosout_agg`, `/rqt` the rqt tools'
  own nodes). Dead sinks are topics nobody subscribes to; leaf topics are topics only one node
  uses. Both are judged after the node and topic filters.
- A filter is a comma-separated list of regular expressions searched in the name; one
  starting with `-` excludes what it matches. No include pattern means everything.
- Grouping puts each node and topic in a cluster named after its namespace (`/turtle1`).
- Grouping actions (rqt_graph's "Group: Actions", in the topic modes) draws the five topics of
  an action (`ns/goal`, `cancel`, `status`, `feedback`, `result`, all five shown) as one box,
  `ns/action_topics`, joined to every node that uses any of them.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from enum import Enum
from typing import Any

from kame import names

QUIET_NAMES = ("/diag_agg", "/runtime_logger", "/pr2_dashboard", "/rviz", "/rosout", "/cpu_monitor", "/monitor",
               "/hd_monitor", "/rxloggerlevel", "/clock", "/rqt", "/statistics")


class Mode(Enum):
    NODES_ONLY = "Nodes only"
    NODES_TOPICS_ACTIVE = "Nodes/Topics (active)"
    NODES_TOPICS_ALL = "Nodes/Topics (all)"


# the names `rqt_graph --mode` takes
MODE_BY_OPTION = {"nodes": Mode.NODES_ONLY, "active": Mode.NODES_TOPICS_ACTIVE, "all": Mode.NODES_TOPICS_ALL}


class Kind(Enum):
    NODE = "node"
    TOPIC = "topic"


@dataclass(frozen=True, order=True)
class Link:
    """A live connection: `publisher` sends `topic` to `subscriber` (node names)."""

    publisher: str
    subscriber: str
    topic: str


@dataclass(frozen=True)
class GraphSnapshot:
    publishers: Mapping[str, tuple[str, ...]]  # topic -> the nodes registered as its publishers
    subscribers: Mapping[str, tuple[str, ...]]
    nodes: frozenset[str]  # every node the master named (services included)
    links: frozenset[Link] = frozenset()
    unreachable: frozenset[str] = frozenset()


def snapshot_from(system_state: Sequence[Sequence[Any]], bus_info: Mapping[str, Sequence[Sequence[Any]] | None],
                  node_uris: Mapping[str, str]) -> GraphSnapshot:
    """A snapshot from getSystemState's value, each node's getBusInfo value (None when the node
    did not answer) and the nodes' XML-RPC URIs (inbound connections name their publisher by URI)."""
    def registrations(part: Sequence[Any]) -> dict[str, tuple[str, ...]]:
        return {str(topic): tuple(sorted({str(n) for n in nodes})) for topic, nodes in part}

    publishers = registrations(system_state[0]) if len(system_state) > 0 else {}
    subscribers = registrations(system_state[1]) if len(system_state) > 1 else {}
    nodes: set[str] = set()
    for part in system_state[:3]:
        for _, members in part:
            nodes.update(str(n) for n in members)
    by_uri = {_normal_uri(uri): node for node, uri in node_uris.items()}
    links: set[Link] = set()
    for node, info in bus_info.items():
        for entry in info or ():
            link = _link_of(node, entry, by_uri)
            if link is not None:
                links.add(link)
    unreachable = frozenset(n for n in nodes if bus_info.get(n) is None)
    return GraphSnapshot(publishers, subscribers, frozenset(nodes), frozenset(links), unreachable)


def _normal_uri(uri: str) -> str:
    return uri.rstrip("/")


def _link_of(node: str, entry: Sequence[Any], by_uri: Mapping[str, str]) -> Link | None:
    """One getBusInfo row: [id, destination, 'i'|'o', transport, topic, connected, ...]. Outbound
    rows name the subscriber's caller id, inbound ones the publisher's URI."""
    if len(entry) < 5:
        return None
    destination, direction, topic = str(entry[1]), str(entry[2]), str(entry[4])
    if len(entry) > 5 and entry[5] is not True and entry[5] != 1:
        return None
    if direction == "o":
        return Link(node, destination, topic)
    if direction == "i":
        publisher = by_uri.get(_normal_uri(destination))
        if publisher is None:
            publisher = destination if destination.startswith("/") else f"unknown ({destination})"
        return Link(publisher, node, topic)
    return None


@dataclass(frozen=True)
class GraphOptions:
    mode: Mode = Mode.NODES_ONLY
    group_namespaces: bool = True
    hide_debug: bool = True
    hide_dead_sinks: bool = True
    hide_leaf_topics: bool = True
    hide_unreachable: bool = False
    node_filter: str = ""
    topic_filter: str = ""
    group_actions: bool = False


@dataclass(frozen=True)
class Vertex:
    id: str  # `n:/name` for a node, `t:/name` for a topic: a node and a topic may share a name
    name: str
    kind: Kind
    unreachable: bool = False


@dataclass(frozen=True)
class SceneEdge:
    source: str  # vertex ids
    target: str
    label: str = ""


@dataclass(frozen=True)
class Group:
    namespace: str
    members: tuple[str, ...]  # vertex ids


@dataclass(frozen=True)
class Scene:
    vertices: tuple[Vertex, ...]
    edges: tuple[SceneEdge, ...]
    groups: tuple[Group, ...] = ()
    _index: dict[str, Vertex] = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self) -> None:
        self._index.update((v.id, v) for v in self.vertices)

    def vertex(self, vertex_id: str) -> Vertex:
        return self._index[vertex_id]

    def names(self, kind: Kind) -> list[str]:
        return sorted(v.name for v in self.vertices if v.kind is kind)

    def edge_names(self) -> list[tuple[str, str, str]]:
        """(source name, target name, label) of every edge, sorted: what tests and docs compare."""
        return sorted((self.vertex(e.source).name, self.vertex(e.target).name, e.label) for e in self.edges)

    def neighbourhood(self, vertex_id: str) -> tuple[set[str], set[int]]:
        """What hovering `vertex_id` highlights: it, the vertices it is joined to, and the joining edges.
        Hovering a topic in nodes-only mode is not possible (topics are edges there)."""
        vertices = {vertex_id}
        edges: set[int] = set()
        for index, edge in enumerate(self.edges):
            if vertex_id in (edge.source, edge.target):
                edges.add(index)
                vertices.update((edge.source, edge.target))
        return vertices, edges


def node_id(name: str) -> str:
    return f"n:{name}"


def topic_id(name: str) -> str:
    return f"t:{name}"


class NameFilter:
    """`a, -b`: names matching a (anywhere), and not b. Bad regular expressions match literally."""

    def __init__(self, text: str) -> None:
        self.include: list[re.Pattern[str]] = []
        self.exclude: list[re.Pattern[str]] = []
        for word in (w.strip() for w in text.split(",")):
            if not word or word == "-":
                continue
            target = self.exclude if word.startswith("-") else self.include
            target.append(_pattern(word[1:] if word.startswith("-") else word))

    def __call__(self, name: str) -> bool:
        if self.include and not any(p.search(name) for p in self.include):
            return False
        return not any(p.search(name) for p in self.exclude)


def _pattern(text: str) -> re.Pattern[str]:
    try:
        return re.compile(text)
    except re.error:
        return re.compile(re.escape(text))


def is_quiet(name: str) -> bool:
    return any(quiet in name for quiet in QUIET_NAMES)


def build_scene(snapshot: GraphSnapshot, options: GraphOptions) -> Scene:
    node_ok = NameFilter(options.node_filter)
    topic_ok = NameFilter(options.topic_filter)

    def keep_node(name: str) -> bool:
        return (node_ok(name) and not (options.hide_debug and is_quiet(name))
                and not (options.hide_unreachable and name in snapshot.unreachable))

    def keep_topic(name: str) -> bool:
        return topic_ok(name) and not (options.hide_debug and is_quiet(name))

    named = set(snapshot.nodes) | {n for link in snapshot.links for n in (link.publisher, link.subscriber)}
    nodes = sorted(n for n in named if keep_node(n))
    kept = set(nodes)
    vertices = [Vertex(node_id(n), n, Kind.NODE, n in snapshot.unreachable) for n in nodes]
    links = sorted(link for link in snapshot.links
                   if link.publisher in kept and link.subscriber in kept and keep_topic(link.topic))
    edges: list[SceneEdge] = []
    if options.mode is Mode.NODES_ONLY:
        edges = [SceneEdge(node_id(link.publisher), node_id(link.subscriber), link.topic) for link in links]
    else:
        if options.mode is Mode.NODES_TOPICS_ACTIVE:
            pubs = _pairs((link.topic, link.publisher) for link in links)
            subs = _pairs((link.topic, link.subscriber) for link in links)
        else:
            pubs = _pairs((t, n) for t, ns in snapshot.publishers.items() for n in ns if n in kept and keep_topic(t))
            subs = _pairs((t, n) for t, ns in snapshot.subscribers.items() for n in ns if n in kept and keep_topic(t))
        if options.group_actions:
            pubs, subs = _group_actions(pubs, set(pubs) | set(subs)), _group_actions(subs, set(pubs) | set(subs))
        for topic in sorted(set(pubs) | set(subs)):
            publishers, subscribers = pubs.get(topic, []), subs.get(topic, [])
            if options.hide_dead_sinks and not subscribers:
                continue
            if options.hide_leaf_topics and len(set(publishers) | set(subscribers)) < 2:
                continue
            vertices.append(Vertex(topic_id(topic), topic, Kind.TOPIC))
            edges += [SceneEdge(node_id(n), topic_id(topic)) for n in publishers]
            edges += [SceneEdge(topic_id(topic), node_id(n)) for n in subscribers]
    groups = _groups(vertices) if options.group_namespaces else []
    return Scene(tuple(vertices), tuple(edges), tuple(groups))


def _pairs(items: Iterable[tuple[str, str]]) -> dict[str, list[str]]:
    found: dict[str, set[str]] = {}
    for key, value in items:
        found.setdefault(key, set()).add(value)
    return {key: sorted(values) for key, values in found.items()}


ACTION_TOPICS = ("goal", "cancel", "status", "feedback", "result")
ACTION_BOX = "action_topics"


def _group_actions(users: dict[str, list[str]], topics: set[str]) -> dict[str, list[str]]:
    """`users` (topic -> nodes) with each complete action's five topics merged into `ns/action_topics`."""
    actions = {ns for ns in (t.rsplit("/", 1)[0] for t in topics if "/" in t.strip("/"))
               if all(f"{ns}/{part}" in topics for part in ACTION_TOPICS)}
    merged: dict[str, set[str]] = {}
    for topic, nodes in users.items():
        namespace, _, last = topic.rpartition("/")
        key = f"{namespace}/{ACTION_BOX}" if namespace in actions and last in ACTION_TOPICS else topic
        merged.setdefault(key, set()).update(nodes)
    return {topic: sorted(nodes) for topic, nodes in merged.items()}


def _groups(vertices: Iterable[Vertex]) -> list[Group]:
    members: dict[str, list[str]] = {}
    for vertex in vertices:
        namespace = names.namespace(vertex.name).rstrip("/")
        if namespace:
            members.setdefault(namespace, []).append(vertex.id)
    return [Group(ns, tuple(ids)) for ns, ids in sorted(members.items())]
