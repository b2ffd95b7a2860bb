"""rosgraph.impl.graph: the ROS computation graph polled from the master and the nodes.

`Graph.update()` asks the master (getSystemState, at most every `master_stale` seconds) and each
node (getBusInfo, at most every `node_stale` seconds, through rosgraph.masterapi.ServerProxy)
and fills `nn_nodes` (node names), `nt_nodes` (topics, as topic_node names), `srvs`, and the
edge lists `nn_edges` (node to node, labelled with the topic), `nt_edges` (node to topic, live
connections) and `nt_all_edges` (node to topic, registrations); it returns whether anything
changed. A node that does not answer is kept in `bad_nodes` and asked again by `bad_update()`.
It runs on the caller's thread and asks one node at a time, as rosgraph's does.
"""

from __future__ import annotations

import itertools
import logging
import random
import sys
import threading
import time
from collections.abc import Iterator

import rosgraph.masterapi
from rosgraph.masterapi import ServerProxy

__all__ = ["BadNode", "Edge", "EdgeList", "Graph", "ServerProxy", "edge_args", "logger", "node_topic", "topic_node"]

logger = logging.getLogger("rosgraph.graph")
_ROS_NAME = "/rosviz"


def topic_node(topic: str) -> str:
    """A topic as a graph node name: a leading space, which no ROS name has, keeps it apart."""
    return " " + topic


def node_topic(node: str) -> str:
    """topic_node's inverse."""
    return node[1:]


class BadNode:
    """A node that did not answer (DEAD), or that answered again after that (WONKY)."""

    DEAD = 0
    WONKY = 1

    def __init__(self, name: str, type: int, reason: str) -> None:
        self.name = name
        self.reason = reason
        self.type = type


class Edge:
    __slots__ = ["end", "key", "label", "rkey", "start"]

    def __init__(self, start: str, end: str, label: str = "") -> None:
        self.start = start
        self.end = end
        self.label = label
        self.key = f"{start}|{label}"
        self.rkey = f"{end}|{label}"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Edge) and self.start == other.start and self.end == other.end

    def __ne__(self, other: object) -> bool:
        return not self == other

    __hash__ = None  # type: ignore[assignment]  # as rosgraph's: edges compare by ends, are not hashed

    def __str__(self) -> str:
        return f"{self.start}->{self.end}"


def edge_args(start: str, dest: str, direction: str, label: str) -> list[tuple[str, str, str]]:
    """The (start, end, label) of the edges for a connection 'o'ut of, 'i'nto or 'b'oth ways of `start`."""
    args = []
    if direction in ("o", "b"):
        args.append((start, dest, label))
    if direction in ("i", "b"):
        args.append((dest, start, label))
    return args


class EdgeList:
    """Edges by `start|label` and by `end|label`."""

    __slots__ = ["edges_by_end", "edges_by_start"]

    def __init__(self) -> None:
        self.edges_by_start: dict[str, list[Edge]] = {}
        self.edges_by_end: dict[str, list[Edge]] = {}

    def __iter__(self) -> Iterator[Edge]:
        return itertools.chain(*self.edges_by_start.values())

    def has(self, edge: Edge) -> bool:
        return edge in self

    def __contains__(self, edge: object) -> bool:
        return isinstance(edge, Edge) and edge in self.edges_by_start.get(edge.key, [])

    def add(self, edge: Edge) -> bool:
        """Add `edge`; whether it was new."""
        def update(edges: dict[str, list[Edge]], key: str) -> bool:
            present = edges.setdefault(key, [])
            if edge in present:
                return False
            present.append(edge)
            return True

        added = update(self.edges_by_start, edge.key)
        return update(self.edges_by_end, edge.rkey) or added

    def add_edges(self, start: str | None, dest: str | None, direction: str, label: str = "") -> bool:
        """Add the edges edge_args gives; whether any was new (none when an end is unknown)."""
        if not start:
            logger.warning("cannot add edge: cannot map start [%s] to a node name", start)
            return False
        if not dest:
            logger.warning("cannot add edge: cannot map dest [%s] to a node name", dest)
            return False
        updated = False
        for args in edge_args(start, dest, direction, label):
            updated = self.add(Edge(*args)) or updated
        return updated

    def delete_all(self, node: str) -> None:
        """Remove every edge that starts or ends at `node`."""
        prefix = node + "|"
        for edges in [v for k, v in itertools.chain(self.edges_by_start.items(), self.edges_by_end.items())
                      if k.startswith(prefix)]:
            for edge in list(edges):
                self.delete(edge)

    def delete(self, edge: Edge) -> None:
        for edges, key in ((self.edges_by_start, edge.key), (self.edges_by_end, edge.rkey)):
            if edge in edges.get(key, []):
                edges[key].remove(edge)


class Graph:
    """The graph below `node_ns` and `topic_ns`; not thread-safe."""

    def __init__(self, node_ns: str = "/", topic_ns: str = "/") -> None:
        self.master = rosgraph.masterapi.Master(_ROS_NAME)
        self.node_ns = node_ns or "/"
        self.topic_ns = topic_ns or "/"
        self.nn_nodes: set[str] = set()
        self.nt_nodes: set[str] = set()
        self.bad_nodes: dict[str, BadNode] = {}
        self.bad_nodes_lock = threading.Lock()
        self.srvs: set[str] = set()
        self.nn_edges = EdgeList()
        self.nt_edges = EdgeList()
        self.nt_all_edges = EdgeList()
        self.node_uri_map: dict[str, str] = {}
        self.uri_node_map: dict[str, str] = {}
        self.last_master_refresh = 0.0
        self.last_node_refresh: dict[str, float] = {}
        self.master_stale = 5.0
        self.node_stale = 5.0

    def set_master_stale(self, stale_secs: float) -> None:
        self.master_stale = stale_secs

    def set_node_stale(self, stale_secs: float) -> None:
        self.node_stale = stale_secs

    def _master_refresh(self) -> bool:
        try:
            pubs, subs, srvs = self.master.getSystemState()
        except (rosgraph.masterapi.MasterException, OSError) as exc:
            print("Unable to contact master", str(exc), file=sys.stderr)
            logger.error("unable to contact master: %s", exc)
            return False
        updated = False
        nodes: set[str] = set()
        for state, direction in ((pubs, "o"), (subs, "i")):
            for topic, members in state:
                if topic.startswith(self.topic_ns):
                    nodes.update(n for n in members if n.startswith(self.node_ns))
                    self.nt_nodes.add(topic_node(topic))
                    for node in members:
                        updated = self.nt_all_edges.add_edges(node, topic_node(topic), direction) or updated
        services = {s for s, _ in srvs}
        purge = self.nn_nodes - nodes
        if nodes ^ self.nn_nodes:
            self.nn_nodes = nodes
            updated = True
        if services ^ self.srvs:
            self.srvs = services
            updated = True
        for node in purge:
            self.nn_edges.delete_all(node)
            self.nt_edges.delete_all(node)
            self.nt_all_edges.delete_all(node)
        return updated

    def _mark_bad_node(self, node: str, reason: str) -> None:
        with self.bad_nodes_lock:
            if node in self.bad_nodes:
                self.bad_nodes[node].type = BadNode.DEAD
            else:
                self.bad_nodes[node] = BadNode(node, BadNode.DEAD, reason)

    def _unmark_bad_node(self, node: str, reason: str = "") -> None:
        with self.bad_nodes_lock:
            self.bad_nodes[node].type = BadNode.WONKY

    def _node_refresh_businfo(self, node: str, api: ServerProxy, bad_node: bool = False) -> bool:
        """`api`'s getBusInfo into the edges (rosgraph's waits 1 s, 0.2 s for a bad node: the
        proxies _node_refresh makes wait as long)."""
        if bad_node:
            self._unmark_bad_node(node)
        try:
            code, msg, bus_info = api.getBusInfo(_ROS_NAME)
        except Exception as exc:  # whatever went wrong, the node is bad
            self._mark_bad_node(node, str(exc))
            code, msg, bus_info = -1, str(exc), []
        if code != 1:
            logger.error("cannot get stats info from node [%s]: %s", node, msg)
            return False
        updated = False
        for info in bus_info:
            if len(info) < 5:
                continue
            dest_id, direction, topic = info[1], info[2], info[4]
            connected = info[5] if len(info) > 5 else True
            if connected and topic.startswith(self.topic_ns):
                self.nt_nodes.add(topic_node(topic))
                updated = self.nt_edges.add_edges(node, topic_node(topic), direction) or updated
                if dest_id.startswith("http://"):
                    updated = self.nn_edges.add_edges(node, self.uri_node_map.get(dest_id), direction,
                                                      topic) or updated
        return updated

    def _node_refresh(self, node: str, bad_node: bool = False) -> bool:
        uri = self._node_uri_refresh(node)
        if uri is None:
            return False
        return self._node_refresh_businfo(node, ServerProxy(uri, timeout=0.2 if bad_node else 1.0), bad_node)

    def _node_uri_refresh(self, node: str) -> str | None:
        try:
            uri = str(self.master.lookupNode(node))
        except Exception as exc:  # any failure of the lookup leaves the node without a URI
            logger.warning("master reported error in node lookup: %s", exc)
            return None
        self.node_uri_map[node] = uri
        self.uri_node_map[uri] = node
        return uri

    def _node_uri_refresh_all(self) -> None:
        for node in self.nn_nodes:
            self._node_uri_refresh(node)

    def _refresh_due(self, node: str, bad: bool) -> bool:
        if time.time() <= self.last_node_refresh.get(node, 0.0) + self.node_stale:
            return False
        updated = self._node_refresh(node, bad)
        self.last_node_refresh[node] = time.time() + random.random() * self.node_stale / 5.0
        return updated

    def bad_update(self) -> bool:
        """Ask the nodes that did not answer before; whether anything changed."""
        with self.bad_nodes_lock:
            queue = [bad.name for bad in self.bad_nodes.values()]
        updated = False
        for node in queue:
            updated = self._refresh_due(node, True) or updated
        return updated

    def update(self) -> bool:
        """Refresh what is stale, the master first; whether anything changed."""
        updated = False
        if time.time() > self.last_master_refresh + self.master_stale:
            updated = self._master_refresh()
            if self.last_master_refresh == 0:
                self._node_uri_refresh_all()
            self.last_master_refresh = time.time()
        for node in list(self.nn_nodes):
            updated = self._refresh_due(node, False) or updated
        return updated
