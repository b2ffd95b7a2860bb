"""rosnode: list, info, ping, kill, cleanup and machine, as ros_comm's rosnode behaves.

Nodes are reached over their XML-RPC API through kame.node (getPid, getBusInfo, shutdown),
the master through kame.cli._tool. Options are parsed as the real tool's optparse does
(kame.cli._options), so usage errors look the same (`rosnode: error: ...`, exit 2). As in the real tool, a failed
ping reports on stderr and still exits 0. Deliberate differences: `ping --all` pings in sorted
order (the real one in set order), and `cleanup` treats end of input as `n`.
"""

from __future__ import annotations

import errno
import os
import sys
import time
from collections.abc import Sequence
from urllib.parse import urlsplit

from kame.cli import _nodeinfo
from kame.cli._options import OptionParser
from kame.cli._tool import Master, ToolError, node_names, run, script_resolve_name
from kame.net import interfaces
from kame.node.master_proxy import MasterError, MasterProxy
from kame.protocol.xmlrpc import XmlRpcError

NAME = "rosnode"
ID = "/rosnode"
PING_TIMEOUT = 3.0
INFO_TIMEOUT = 5.0

USAGE = """rosnode is a command-line tool for printing information about ROS Nodes.

Commands:
\trosnode ping\ttest connectivity to node
\trosnode list\tlist active nodes
\trosnode info\tprint information about node
\trosnode machine\tlist nodes running on a particular machine or list machines
\trosnode kill\tkill a running node
\trosnode cleanup\tpurge registration information of unreachable nodes

Type rosnode <command> -h for more detailed usage, e.g. 'rosnode ping -h'
"""


class Graph:
    """The master as rosnode uses it, with node URIs cached as the real tool caches them."""

    def __init__(self) -> None:
        self.master = Master(ID)
        self._uris: dict[str, str] = {}

    def uri(self, node: str, skip_cache: bool = False) -> str | None:
        if skip_cache or node not in self._uris:
            found = self.master.lookup_node(node)
            if found is None:
                return None
            self._uris[node] = found
        return self._uris[node]

    def forget(self, node: str) -> None:
        self._uris.pop(node, None)

    def nodes(self, namespace: str | None = None) -> list[str]:
        return node_names(self.master.system_state(), namespace)


def _node_call(uri: str, method: str, timeout: float, *args: object) -> object:
    """Call a node's API as /rosnode; a failure code raises ToolError, transport errors OSError."""
    proxy = MasterProxy(uri, ID, timeout=timeout)
    try:
        return proxy.call(method, *args)
    except MasterError as exc:
        raise ToolError(f"remote call failed: {exc.message}") from None
    except XmlRpcError as exc:
        raise OSError(str(exc)) from exc
    finally:
        proxy.close()


def _bus_stats(uri: str) -> object:
    """A node's getBusStats: rospy's and kame's answer [code, text, stats], roscpp's the stats alone."""
    proxy = MasterProxy(uri, ID, timeout=INFO_TIMEOUT)
    try:
        answer = proxy.call_raw("getBusStats")
    finally:
        proxy.close()
    if isinstance(answer, list) and len(answer) == 3 and type(answer[0]) is int:
        return answer[2] if answer[0] == 1 else None
    return answer


def _cause(exc: BaseException) -> BaseException:
    while exc.__cause__ is not None:
        exc = exc.__cause__
    return exc


# ------------------------------------------------------------------ ping


def ping(graph: Graph, node: str, max_count: int | None = None, verbose: bool = False,
         skip_cache: bool = False) -> bool:
    uri = graph.uri(node, skip_cache=skip_cache)
    if not uri:
        print(f"cannot ping [{node}]: unknown node", file=sys.stderr)
        return False
    if verbose:
        print(f"pinging {node} with a timeout of {PING_TIMEOUT}s", flush=True)
    count = 0
    total = 0.0
    try:
        while True:
            start = time.perf_counter()
            try:
                _node_call(uri, "getPid", PING_TIMEOUT)
            except OSError as exc:
                cause = _cause(exc)
                if isinstance(cause, TimeoutError):
                    print(f"connection to [{node}] timed out", file=sys.stderr)
                elif isinstance(cause, interfaces.UnknownHostError):
                    print(f"ERROR: Unknown host [{urlsplit(uri).hostname}] for node [{node}]", file=sys.stderr)
                elif isinstance(cause, ConnectionRefusedError) or getattr(cause, "errno", None) == errno.ECONNREFUSED:
                    new_uri = graph.uri(node, skip_cache=True)
                    if not new_uri:
                        print(f"cannot ping [{node}]: unknown node", file=sys.stderr)
                        return False
                    if new_uri != uri:
                        if verbose:
                            print(f"node url has changed from [{uri}] to [{new_uri}], retrying to ping")
                        uri = new_uri
                        continue
                    print(f"ERROR: connection refused to [{uri}]", file=sys.stderr)
                else:
                    print(f"connection to [{node}] failed", file=sys.stderr)
                return False
            elapsed = (time.perf_counter() - start) * 1000.0
            total += elapsed
            count += 1
            if verbose:
                print(f"xmlrpc reply from {uri}\ttime={elapsed:f}ms", flush=True)
            if max_count and count >= max_count:
                break
            time.sleep(1.0)
    except KeyboardInterrupt:
        pass
    if verbose and count > 1:
        print(f"ping average: {total / count:f}ms")
    return True


def ping_all(graph: Graph, verbose: bool = False) -> tuple[list[str], list[str]]:
    nodes = graph.nodes()
    if verbose:
        print("Will ping the following nodes: \n" + "".join(f" * {n}\n" for n in nodes))
    pinged: list[str] = []
    unpinged: list[str] = []
    for node in nodes:
        (pinged if ping(graph, node, max_count=1, verbose=verbose) else unpinged).append(node)
    return pinged, unpinged


# ------------------------------------------------------------------ commands


def _parser(usage: str) -> OptionParser:
    return OptionParser(usage=usage, prog=NAME)


def cmd_list(argv: list[str]) -> None:
    parser = _parser("usage: %prog list")
    parser.add_argument("-u", dest="list_uri", default=False, action="store_true", help="list XML-RPC URIs")
    parser.add_argument("-a", "--all", dest="list_all", default=False, action="store_true",
                      help="list all information")
    options = parser.parse_args(argv)
    args = options.args
    namespace = None
    if len(args) > 1:
        parser.error("invalid args: you may only specify one namespace")
    elif args:
        namespace = script_resolve_name("rostopic", args[0])
    graph = Graph()
    nodes = graph.nodes(namespace)
    if options.list_all:
        print("\n".join(f"{graph.uri(n) or 'unknown address'} \t{n}" for n in nodes))
    elif options.list_uri:
        print("\n".join(graph.uri(n) or "unknown address" for n in nodes))
    else:
        print("\n".join(nodes))


def info(graph: Graph, node: str, quiet: bool) -> None:
    master = graph.master
    state = master.system_state()
    published = master.call("getPublishedTopics", "/")
    print(_nodeinfo.SEPARATOR)
    print(_nodeinfo.describe(node, state, published))
    uri = graph.uri(node)
    if not uri:
        print(f"cannot contact [{node}]: unknown node", file=sys.stderr)
        return
    if quiet:
        return
    print(f"\ncontacting node {uri} ...", flush=True)
    try:
        pid = _node_call(uri, "getPid", INFO_TIMEOUT)
        bus_info = _node_call(uri, "getBusInfo", INFO_TIMEOUT)
    except OSError:
        raise ToolError(f"Communication with node[{uri}] failed!") from None
    try:
        dropped = _nodeinfo.drop_counts(_bus_stats(uri))
    except (OSError, XmlRpcError):  # counts are extra: a node that cannot say has none shown
        dropped = {}
    print(_nodeinfo.connections(pid, bus_info if isinstance(bus_info, list) else [], state, graph.uri, dropped))


def cmd_info(argv: list[str]) -> None:
    parser = _parser("usage: %prog info [options] node1 [node2...]")
    parser.add_argument("-q", "--quiet", dest="quiet", default=False, action="store_true",
                      help="Prints only basic information such as pubs/subs and does not contact nodes for "
                           "more information")
    options = parser.parse_args(argv)
    args = options.args
    if not args:
        parser.error("You must specify at least one node name")
    graph = Graph()
    for node in args:
        info(graph, script_resolve_name(NAME, node), options.quiet)


def _addresses(host: str) -> list[str]:
    found = interfaces.resolve(host)
    if found is None:
        raise OSError(f"cannot resolve {host}")
    return found


def cmd_machine(argv: list[str]) -> None:
    parser = _parser("usage: %prog machine [machine-name]")
    parsed = parser.parse_args(argv)
    args = parsed.args
    if len(args) > 1:
        parser.error("please enter only one machine name")
    graph = Graph()
    if not args:
        machines: list[str] = []
        for node in graph.nodes():
            uri = graph.uri(node)
            host = urlsplit(uri).hostname if uri else None
            if host and host not in machines:
                machines.append(host)
        print("\n".join(sorted(machines)))
        return
    machine = args[0]
    try:
        wanted = set(_addresses(machine))
    except OSError:
        raise ToolError(f"cannot resolve machine name [{machine}] to address") from None
    found: list[str] = []
    for node in graph.nodes():
        uri = graph.uri(node)
        host = urlsplit(uri).hostname if uri else None
        if not host:
            continue
        if host == machine or host in wanted:
            found.append(node)
            continue
        try:
            if set(_addresses(host)) & wanted:
                found.append(node)
        except OSError:
            continue
    print("\n".join(sorted(found)))


def kill(graph: Graph, nodes: list[str]) -> list[str]:
    """Ask each node to shut down; returns the names the master did not know."""
    failed: list[str] = []
    targets: list[tuple[str, str]] = []
    for node in nodes:
        uri = graph.uri(node)
        if uri is None:
            failed.append(node)
        else:
            targets.append((node, uri))
    for _, uri in targets:
        try:  # a node may go away while answering: that is success too
            _node_call(uri, "shutdown", PING_TIMEOUT, "user request")
        except (OSError, ToolError):
            pass
    return failed


def cmd_kill(argv: list[str]) -> int:
    parser = _parser("usage: %prog kill [node]...")
    parser.add_argument("-a", "--all", dest="kill_all", default=False, action="store_true", help="kill all nodes")
    options = parser.parse_args(argv)
    args = options.args
    graph = Graph()
    if options.kill_all:
        if args:
            parser.error("invalid arguments with kill all (-a) option")
        targets = graph.nodes()
    elif not args:
        available = graph.nodes()
        if not available:
            print("No nodes running", file=sys.stderr)
            return 0
        sys.stdout.write("\n".join(f"{i + 1}. {n}" for i, n in enumerate(available)))
        sys.stdout.write("\n\nPlease enter the number of the node you wish to kill.\n> ")
        sys.stdout.flush()
        targets = [available[_read_selection(len(available)) - 1]]
    else:
        targets = [script_resolve_name(NAME, n) for n in args]
        running = set(graph.nodes())
        unknown = [n for n in targets if n not in running]
        if unknown:
            raise ToolError("Unknown node(s):\n" + "\n".join(f" * {n}" for n in unknown))
    if not targets:
        return 0
    if len(targets) > 1:
        print("killing:\n" + "\n".join(f" * {n}" for n in targets))
    else:
        print(f"killing {targets[0]}")
    failed = kill(graph, targets)
    if failed:
        raise ToolError("Failed to kill:\n" + "\n".join(f" * {n}" for n in failed))
    print("killed")
    return 0


def _read_selection(limit: int) -> int:
    while True:
        line = sys.stdin.readline()
        if not line:
            raise KeyboardInterrupt
        try:
            selection = int(line.strip())
        except ValueError:
            print("ERROR: please enter a number (ctrl-C to cancel)", flush=True)
            continue
        if 0 < selection <= limit:
            return selection
        print("ERROR: invalid selection. Please enter a number (ctrl-C to cancel)", flush=True)


def cleanup(graph: Graph) -> None:
    _, unpinged = ping_all(graph)
    if not unpinged:
        return
    print("Unable to contact the following nodes:")
    print("\n".join(f" * {n}" for n in unpinged))
    print("Warning: these might include alive and functioning nodes, e.g. in unstable networks.")
    print("Cleanup will purge all information about these nodes from the master.")
    print("Please type y or n to continue:", flush=True)
    while True:
        answer = sys.stdin.readline()
        if not answer or answer.strip() == "n":
            print("aborting")
            return
        if answer.strip() == "y":
            break
    master = graph.master
    pubs, subs, srvs = master.system_state()
    for node in unpinged:
        print("Unregistering", node)
        uri = graph.uri(node)
        for topic, nodes in pubs:
            if node in nodes:
                _unregister(master, node, "unregisterPublisher", topic, uri)
        for topic, nodes in subs:
            if node in nodes:
                _unregister(master, node, "unregisterSubscriber", topic, uri)
        for service, nodes in srvs:
            if node in nodes:
                try:
                    service_uri = master.call("lookupService", service)
                except MasterError:
                    continue
                _unregister(master, node, "unregisterService", service, service_uri)
        graph.forget(node)
    print("done")


def _unregister(master: Master, node: str, method: str, name: str, uri: str | None) -> None:
    try:
        master.call_as(node, method, name, uri or "")
    except MasterError as exc:
        print(f"ERROR: {method} {name} for {node}: {exc.message}", file=sys.stderr)


def cmd_cleanup(argv: list[str]) -> None:
    _parser("usage: %prog cleanup").parse_args(argv)
    cleanup(Graph())


def cmd_ping(argv: list[str]) -> None:
    parser = _parser("usage: %prog ping [options] <node>")
    parser.add_argument("--all", "-a", dest="ping_all", default=False, action="store_true", help="ping all nodes")
    parser.add_argument("-c", dest="ping_count", default=None, metavar="COUNT", type=int,
                      help="number of pings to send. Not available with --all")
    options = parser.parse_args(argv)
    args = options.args
    node = ""
    if not options.ping_all:
        if not args:
            try:  # the real tool's bare except catches its own first SystemExit: both are printed
                parser.error("Please enter a node to ping. Available nodes are:\n" + "\n".join(Graph().nodes()))
            except (SystemExit, ToolError):
                parser.error("Please enter a node to ping")
        elif len(args) > 1:
            parser.error("you may only specify one input node")
        node = script_resolve_name(NAME, args[0])
        print(f"rosnode: node is [{node}]", flush=True)
    elif args:
        parser.error("Invalid arguments '{}' used with --all".format(" ".join(args)))
    elif options.ping_count:
        parser.error("-c may not be used with --all")
    graph = Graph()
    if options.ping_all:
        ping_all(graph, verbose=True)
    else:
        ping(graph, node, max_count=options.ping_count, verbose=True)


def _main(argv: list[str]) -> int:
    if not argv:
        sys.stdout.write(USAGE + "\n")
        return getattr(os, "EX_USAGE", 1)
    command, rest = argv[0], argv[1:]
    commands = {"ping": cmd_ping, "list": cmd_list, "info": cmd_info, "machine": cmd_machine,
                "cleanup": cmd_cleanup, "kill": cmd_kill}
    if command in commands:
        return commands[command](rest) or 0
    sys.stdout.write(USAGE + "\n")
    return 0 if command == "--help" else getattr(os, "EX_USAGE", 1)


def main(argv: Sequence[str] | None = None) -> int:
    return run(_main, argv)


if __name__ == "__main__":
    sys.exit(main())
