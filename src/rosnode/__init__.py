"""rosnode as a library: node names, pings and kills, as ROS code calls them
(`rosnode.get_node_names()`). The `rosnode` command is kame.cli.rosnode; this module shares
its master queries, pings and shutdown requests (and prints what they print).
"""

from __future__ import annotations

import re
import sys
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from optparse import OptionParser
from typing import Any
from urllib.parse import urlsplit

import rosgraph
import rosgraph.names
from kame.cli import _nodeinfo
from kame.cli import rosnode as _rosnode
from kame.cli._tool import ToolError
from kame.net import interfaces
from rosgraph.masterapi import ServerProxy

__all__ = ["CONNECTION_PATTERN", "ID", "NAME", "OptionParser", "ROSNodeException", "ROSNodeIOException", "ServerProxy",
           "cleanup_master_blacklist", "cleanup_master_whitelist", "get_api_uri", "get_machines_by_nodes",
           "get_node_connection_info_description", "get_node_info_description", "get_node_names",
           "get_nodes_by_machine", "kill_nodes", "lookup_uri", "rosnode_cleanup", "rosnode_debugnode", "rosnode_info",
           "rosnode_listnodes", "rosnode_ping", "rosnode_ping_all", "rosnodemain"]


class ROSNodeException(Exception):
    """Base of rosnode's errors."""


class ROSNodeIOException(ROSNodeException):
    """The master could not be reached."""


@contextmanager
def _graph() -> Iterator[_rosnode.Graph]:
    try:
        graph = _rosnode.Graph()
    except ToolError as exc:
        raise ROSNodeIOException(str(exc)) from None
    try:
        yield graph
    except ToolError as exc:
        raise ROSNodeIOException(str(exc)) from None
    finally:
        graph.master.close()


def get_node_names(namespace: str | None = None) -> list[str]:
    """The nodes that publish, subscribe or provide services, only those under `namespace` if given."""
    with _graph() as graph:
        return graph.nodes(namespace)


def get_api_uri(master: object, caller_id: str, skip_cache: bool = False) -> str | None:
    """The XML-RPC URI of node `caller_id`, or None (`master` is accepted for upstream's signature)."""
    with _graph() as graph:
        return graph.uri(caller_id, skip_cache=skip_cache)


def rosnode_ping(node_name: str, max_count: int | None = None, verbose: bool = False,
                 skip_cache: bool = False) -> bool:
    """Ping the node (once a second, `max_count` times; forever when None); False when it cannot
    be reached."""
    with _graph() as graph:
        return _rosnode.ping(graph, node_name, max_count, verbose, skip_cache)


def rosnode_ping_all(verbose: bool = False) -> tuple[list[str], list[str]]:
    """Ping every node once: (the nodes that answered, those that did not)."""
    with _graph() as graph:
        return _rosnode.ping_all(graph, verbose)


def kill_nodes(node_names: Sequence[str]) -> tuple[list[str], list[str]]:
    """Ask each node to shut down: (the nodes asked, the names the master does not know)."""
    with _graph() as graph:
        failed = _rosnode.kill(graph, list(node_names))
    return [name for name in node_names if name not in failed], failed


# ---------------------------------------------------------------- rosnode's command parts

NAME = _rosnode.NAME
ID = _rosnode.ID
CONNECTION_PATTERN = re.compile(r"\w+ connection on port (\d+) to \[(.*) on socket (\d+)\]")


def get_node_info_description(node_name: str) -> str:
    """What `rosnode info -q` prints for the node: its publications, subscriptions and services."""
    with _graph() as graph:
        master = graph.master
        return _nodeinfo.describe(node_name, master.system_state(), master.call("getPublishedTopics", "/"))


def rosnode_info(node_name: str, quiet: bool = False) -> None:
    """Print `rosnode info` for the node (`quiet`: without asking the node itself)."""
    with _graph() as graph:
        _rosnode.info(graph, rosgraph.names.script_resolve_name(NAME, node_name), quiet)


rosnode_debugnode = rosnode_info  # rosnode's own alias


def rosnode_listnodes(namespace: str | None = None, list_uri: bool = False, list_all: bool = False) -> None:
    """Print the node names (under `namespace`), with their URIs (`list_all`) or the URIs only."""
    with _graph() as graph:
        nodes = graph.nodes(namespace)
        if list_all:
            print("\n".join(f"{graph.uri(n) or 'unknown address'} \t{n}" for n in nodes))
        elif list_uri:
            print("\n".join(graph.uri(n) or "unknown address" for n in nodes))
        else:
            print("\n".join(nodes))


def rosnode_cleanup() -> None:
    """`rosnode cleanup`: offer to purge the nodes that do not answer from the master."""
    with _graph() as graph:
        _rosnode.cleanup(graph)


def rosnodemain(argv: Sequence[str] | None = None) -> None:
    """The rosnode command on `argv` (sys.argv: the program, then the command); ends the process."""
    sys.exit(_rosnode.main(None if argv is None else list(argv)[1:]))


def lookup_uri(master: Any, system_state: Any, topic: str, uri: str) -> str:
    """`node (uri)` for the node of `topic` whose XML-RPC URI is `uri`; `uri` when none is."""
    for entries in system_state[0:2]:
        for entry in entries:
            if entry[0] == topic:
                for node in entry[1]:
                    if str(master.lookupNode(node)) == uri:
                        return f"{node} ({uri})"
    return uri


def get_node_connection_info_description(node_api: str, master: Any) -> str:
    """`Pid: N` and the node's connections, as `rosnode info` prints them."""
    state = master.getSystemState()
    node = ServerProxy(node_api, timeout=5.0)
    try:
        pid = _succeed(node.getPid(ID))
        bus_info = _succeed(node.getBusInfo(ID))
    except OSError:
        raise ROSNodeIOException(f"Communication with node[{node_api}] failed!") from None

    def uri_of(node_name: str) -> str | None:
        try:
            return str(master.lookupNode(node_name))
        except rosgraph.MasterException:
            return None

    return _nodeinfo.connections(pid, bus_info or [], state, uri_of)


def _succeed(answer: Any) -> Any:
    code, message, value = answer
    if code != 1:
        raise ROSNodeException(f"remote call failed: {message}")
    return value


def _hosts() -> Iterator[tuple[str, str]]:
    """(node, the host of its URI) for each node the master knows."""
    master = rosgraph.Master(ID)
    for node in get_node_names():
        try:
            uri = str(master.lookupNode(node))
        except OSError:
            raise ROSNodeIOException("Unable to communicate with master!") from None
        except rosgraph.MasterError:  # gone between the two calls: not there
            continue
        host = urlsplit(uri).hostname
        if host:
            yield node, host


def get_machines_by_nodes() -> list[str]:
    """The hosts the nodes' URIs name, each once, in the nodes' order."""
    return list(dict.fromkeys(host for _node, host in _hosts()))


def get_nodes_by_machine(machine: str) -> list[str]:
    """The nodes whose URI names `machine` or a host of the same address."""
    wanted = interfaces.resolve(machine)
    if wanted is None:
        raise ROSNodeException(f"cannot resolve machine name [{machine}] to address")
    found = []
    for node, host in _hosts():
        addresses = [host] if host == machine else interfaces.resolve(host) or []
        if host == machine or set(addresses) & set(wanted):
            found.append(node)
    return found


def _unregister_all(master: Any, node: str, pubs: Any, subs: Any, srvs: Any) -> None:
    node_api = get_api_uri(master, node) or ""
    as_node = rosgraph.Master(node)
    for topic, nodes in pubs:
        if node in nodes:
            as_node.unregisterPublisher(topic, node_api)
    for topic, nodes in subs:
        if node in nodes:
            as_node.unregisterSubscriber(topic, node_api)
    for service, nodes in srvs:
        if node in nodes:
            as_node.unregisterService(service, master.lookupService(service))


def cleanup_master_blacklist(master: Any, blacklist: Sequence[str]) -> None:
    """Take every registration of the nodes in `blacklist` off the master."""
    pubs, subs, srvs = master.getSystemState()
    for node in blacklist:
        print("Unregistering", node)
        _unregister_all(master, node, pubs, subs, srvs)


def cleanup_master_whitelist(master: Any, whitelist: Sequence[str]) -> None:
    """Take every registration of the nodes not in `whitelist` off the master."""
    pubs, subs, srvs = master.getSystemState()
    others = {n for part in (pubs, subs, srvs) for _name, nodes in part for n in nodes if n not in whitelist}
    for node in sorted(others):
        _unregister_all(master, node, pubs, subs, srvs)
