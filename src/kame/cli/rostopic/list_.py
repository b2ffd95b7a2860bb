"""rostopic list [/namespace] [-v] [-p] [-s] [--host] [-b BAGFILE]."""

from __future__ import annotations

from urllib.parse import urlparse

from kame import names

from ._common import bag_errors, master, open_bag, option_parser, script_resolve_name, topic_list


def _print_list(pubs: list[tuple[str, str, list[str]]], subs: list[tuple[str, str, list[str]]],
                publishers_only: bool, subscribers_only: bool, verbose: bool, indent: str = "") -> None:
    if verbose:
        lines: list[str] = []
        if not subscribers_only:
            lines.append(f"\n{indent}Published topics:")
            for t, ty, nodes in pubs:
                count = f"{len(nodes)} publishers" if len(nodes) > 1 else "1 publisher"
                lines.append(f"{indent} * {t} [{ty}] {count}")
        if not publishers_only:
            lines.append(indent)
            lines.append(f"{indent}Subscribed topics:")
            for t, ty, nodes in subs:
                count = f"{len(nodes)} subscribers" if len(nodes) > 1 else "1 subscriber"
                lines.append(f"{indent} * {t} [{ty}] {count}")
        lines.append("")
        print("\n".join(lines))
        return
    if publishers_only:
        topics = [t for t, _, _ in pubs]
    elif subscribers_only:
        topics = [t for t, _, _ in subs]
    else:
        topics = list({t for t, _, _ in pubs} | {t for t, _, _ in subs})
    print("\n".join(indent + t for t in sorted(topics)))


def _bag_list(path: str, topic: str | None, verbose: bool) -> None:
    with open_bag(path) as bag:
        info = bag.get_type_and_topic_info()
    topics = sorted(info.topics)
    if topic:
        ns = names.make_global_ns(topic)
        topics = [t for t in topics if t == topic or t.startswith(ns)]
    if verbose:
        print("\nPublished topics:")
        for t in topics:
            print(f" * {t} [{info.topics[t].msg_type}] {info.topics[t].message_count} msgs")
        return
    print("\n".join(topics))


def cmd_list(args: list[str]) -> None:
    parser = option_parser("usage: %prog list [/namespace]")
    parser.add_argument("-b", "--bag", dest="bag", default=None, help="list topics in .bag file", metavar="BAGFILE")
    parser.add_argument("-v", "--verbose", dest="verbose", default=False, action="store_true",
                      help="list full details about each topic")
    parser.add_argument("-p", dest="publishers", default=False, action="store_true", help="list only publishers")
    parser.add_argument("-s", dest="subscribers", default=False, action="store_true", help="list only subscribers")
    parser.add_argument("--host", dest="hostname", default=False, action="store_true", help="group by host name")
    options = parser.parse_args(args)
    rest = options.args
    topic = None
    if len(rest) == 1:
        topic = script_resolve_name(rest[0])
    elif len(rest) > 1:
        parser.error("you may only specify one input topic")
    if options.bag:
        if options.subscribers:
            parser.error("-s option is not valid with bags")
        elif options.publishers:
            parser.error("-p option is not valid with bags")
        elif options.hostname:
            parser.error("--host option is not valid with bags")
        with bag_errors():
            _bag_list(options.bag, topic, options.verbose)
        return
    if options.subscribers and options.publishers:
        parser.error("you may only specify one of -p, -s")
    pubs, subs = topic_list()
    if topic:
        ns = names.make_global_ns(topic)
        pubs = [x for x in pubs if x[0] == topic or x[0].startswith(ns)]
        subs = [x for x in subs if x[0] == topic or x[0].startswith(ns)]
    if not options.hostname:
        _print_list(pubs, subs, options.publishers, options.subscribers, options.verbose)
        return
    uris: dict[str, str] = {}

    def by_host(entries: list[tuple[str, str, list[str]]]) -> dict[str, list[tuple[str, str, list[str]]]]:
        hosts: dict[str, list[tuple[str, str, list[str]]]] = {}
        for t, ty, nodes in entries:
            for node in nodes:
                if node not in uris:
                    uris[node] = str(master().call("lookupNode", node))
                host = urlparse(uris[node]).hostname or ""
                rows = hosts.setdefault(host, [])
                for row in rows:
                    if row[0] == t:
                        row[2].append(node)
                        break
                else:
                    rows.append((t, ty, [node]))
        return hosts

    host_pubs, host_subs = by_host(pubs), by_host(subs)
    for host in sorted(set(host_pubs) | set(host_subs)):
        p, s = host_pubs.get(host, []), host_subs.get(host, [])
        if (p and not options.subscribers) or (s and not options.publishers):
            print(f"Host [{host}]:")
            _print_list(p, s, options.publishers, options.subscribers, options.verbose, indent="  ")
