"""rostopic info /topic: its type, publishers and subscribers."""

from __future__ import annotations

from ._common import (
    MasterUnreachable,
    RostopicError,
    master,
    option_parser,
    script_resolve_name,
    topic_list,
    topic_types,
)


def info_text(topic: str) -> str:
    pubs, subs = topic_list()
    pubs = [x for x in pubs if x[0] == topic]
    subs = [x for x in subs if x[0] == topic]
    if not pubs and not subs:
        raise RostopicError(f"Unknown topic {topic}")
    types = dict(reversed(topic_types()))
    uris: dict[str, str] = {}

    def api(node: str) -> str:
        if node not in uris:
            try:
                uris[node] = str(master().call("lookupNode", node))
            except MasterUnreachable:
                raise
            except RostopicError:
                uris[node] = f"unknown address {node}"
        return uris[node]

    out = [f"Type: {types.get(topic, 'unknown type')}\n\n"]
    for title, entries in (("Publishers", pubs), ("Subscribers", subs)):
        if entries:
            out.append(f"{title}: \n")
            out.extend(f" * {node} ({api(node)})\n" for _, _, nodes in entries for node in nodes)
        else:
            out.append(f"{title}: None\n")
        out.append("\n")
    return "".join(out)


def cmd_info(args: list[str]) -> None:
    parser = option_parser("usage: %prog info /topic")
    options = parser.parse_args(args)
    rest = options.args
    if not rest:
        parser.error("you must specify a topic name")
    elif len(rest) > 1:
        parser.error("you may only specify one topic name")
    print(info_text(script_resolve_name(rest[0])))
