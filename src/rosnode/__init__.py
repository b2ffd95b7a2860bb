"""rosnode as a library: node names, pings and kills, as ROS code calls them
(`rosnode.get_node_names()`). The `rosnode` command is kame.cli.rosnode; this module shares
its master queries, pings and shutdown requests (and prints what they print).
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from contextlib import contextmanager

from kame.cli import rosnode as _rosnode
from kame.cli._tool import ToolError

__all__ = ["ROSNodeException", "ROSNodeIOException", "get_api_uri", "get_node_names", "kill_nodes",
           "rosnode_ping", "rosnode_ping_all"]


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
