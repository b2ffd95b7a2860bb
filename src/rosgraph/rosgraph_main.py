"""rosgraph's command: the graph's nodes, their connections and the services, once a second."""

from __future__ import annotations

import sys
import threading

from . import masterapi, roslogging
from .impl import graph

__all__ = ["fullusage", "rosgraph_main"]


def fullusage() -> None:
    print("""rosgraph is a command-line tool for debugging the ROS Computation Graph.

Usage:
\trosgraph
""")


def _print_graph(g: graph.Graph) -> None:
    if not g.nn_nodes and not g.srvs:
        print("empty")
    else:
        print("\n")
    if g.nn_nodes:
        print("Nodes:")
        for node in g.nn_nodes:
            prefix = node + "|"
            print("  " + node + " :")
            print("    Inbound:")
            for key, edges in g.nn_edges.edges_by_end.items():
                if key.startswith(prefix):
                    for edge in edges:
                        print("      " + edge.start)
            print("    Outbound:")
            for key, edges in g.nn_edges.edges_by_start.items():
                if key.startswith(prefix):
                    for edge in edges:
                        print("      " + edge.end)
    if g.srvs:
        print("Services:")
        for service in g.srvs:
            print("  " + service)
    sys.stdout.flush()


def rosgraph_main() -> None:
    """`rosgraph`: print the graph every second until Ctrl-C (`-h`: the usage)."""
    if len(sys.argv) == 2 and sys.argv[1] in ("-h", "--help"):
        fullusage()
        return
    if len(sys.argv) != 1:
        fullusage()
        sys.exit(-1)
    roslogging.configure_logging("rosgraph")
    master = masterapi.Master("rosgraph")
    try:
        master.getPid()
    except Exception:  # any failure to reach the master is this one line, as rosgraph's
        print("ERROR: Unable to communicate with master!", file=sys.stderr)
        return
    g = graph.Graph()
    interval = threading.Event()  # never set: the pause between pictures
    try:
        while True:
            g.update()
            _print_graph(g)
            interval.wait(1.0)
    except KeyboardInterrupt:
        pass
