"""The text of `rosnode info`, from what the master and the node answered (pure).

- Publications, subscriptions and services are sorted; an empty list prints `None`.
- A topic's type is looked up among PUBLISHED topics, so a topic nobody publishes shows
  `[unknown type]`.
- Connections come from the node's getBusInfo, in its order; only connected ones are shown.
  The peer is named `node (uri)` when the URI is one of the topic's registered nodes, and
  rospy's transport description adds `(port - peer) [fd]` to the direction.
- A connection whose queue has dropped messages says how many (`* dropped:`, kame's line,
  from getBusStats); one that dropped none prints as rosnode does.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from typing import Any

SEPARATOR = "-" * 80
SystemState = tuple[list[tuple[str, list[str]]], ...]

# The text of rospy's TCPROSTransport.get_transport_info.
_CONNECTION = re.compile(r"\w+ connection on port (\d+) to \[(.*) on socket (\d+)\]")


def _topic_type(topic: str, published: Sequence[Sequence[str]]) -> str:
    for name, type_name in published:
        if name == topic:
            return type_name
    return "unknown type"


def describe(node: str, state: SystemState, published: Sequence[Sequence[str]]) -> str:
    """The record printed after the separator: `Node [/x]` and its three lists."""
    pubs = sorted(t for t, nodes in state[0] if node in nodes)
    subs = sorted(t for t, nodes in state[1] if node in nodes)
    srvs = sorted(s for s, nodes in state[2] if node in nodes)
    text = f"Node [{node}]"
    for title, items in (("Publications", [f" * {t} [{_topic_type(t, published)}]" for t in pubs]),
                         ("Subscriptions", [f" * {t} [{_topic_type(t, published)}]" for t in subs]),
                         ("Services", [f" * {s}" for s in srvs])):
        if items:
            text += f"\n{title}: \n" + "\n".join(items) + "\n"
        else:
            text += f"\n{title}: None\n"
    return text


def peer_name(state: SystemState, topic: str, dest: str, lookup: Callable[[str], str | None]) -> str:
    """`node (uri)` when `dest` is the URI of a node registered on `topic`, else `dest` itself."""
    for part in state[:2]:
        for name, nodes in part:
            if name == topic:
                for n in nodes:
                    if lookup(n) == dest:
                        return f"{n} ({dest})"
    return dest


def drop_counts(bus_stats: Any) -> dict[int, int]:
    """Messages dropped by each connection's queue (by connection id), from a getBusStats
    answer's stats: a subscription's drop estimate (roscpp's and kame's; rospy says -1) and the
    fifth field kame's publication rows add after rospy's four (roscpp's rows have no byte
    total, and their fifth field is not a count)."""
    counts: dict[int, int] = {}
    try:
        publications, subscriptions = bus_stats[0], bus_stats[1]
        for row in (row for *_, rows in publications for row in rows):
            if len(row) == 5 and isinstance(row[3], bool) and isinstance(row[4], int):
                counts[row[0]] = row[4]
        for row in (row for _, rows in subscriptions for row in rows):
            if len(row) == 5 and isinstance(row[3], int) and row[3] >= 0:
                counts[row[0]] = row[3]
    except (TypeError, ValueError, IndexError):  # an answer of another shape: no counts
        return {}
    return counts


def connections(pid: Any, bus_info: Sequence[Sequence[Any]], state: SystemState,
                lookup: Callable[[str], str | None], dropped: dict[int, int] | None = None) -> str:
    """`Pid: N` and the `Connections:` list; `dropped` from drop_counts."""
    text = f"Pid: {pid}\n"
    if not bus_info:
        return text
    text += "Connections:\n"
    for info in bus_info:
        dest, direction, transport, topic = info[1], info[2], info[3], info[4]
        connected = info[5] if len(info) > 5 else True
        if not connected:
            continue
        text += f" * topic: {topic}\n"
        text += f"    * to: {peer_name(state, str(topic), str(dest), lookup)}\n"
        text += {"i": "    * direction: inbound", "o": "    * direction: outbound"}.get(
            str(direction), "    * direction: unknown")
        if len(info) > 6:
            match = _CONNECTION.match(str(info[6]))
            if match is not None:
                text += " ({} - {}) [{}]".format(*match.groups())
        text += f"\n    * transport: {transport}\n"
        drops = (dropped or {}).get(info[0], 0)
        if drops:
            text += f"    * dropped: {drops} (its queue was full)\n"
    return text
