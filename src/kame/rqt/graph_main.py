"""rqt_graph: the ROS computation graph in a window, or once into a file.

    rqt_graph [--mode nodes|active|all] [--node-filter F] [--topic-filter F] [--show-debug]
              [--show-dead-sinks] [--show-leaf-topics] [--hide-unreachable] [--no-groups] [--group-actions]
              [--output FILE.svg|.dot|.png]

With --output there is no window: the graph is asked once, laid out and written (SVG and dot
need no Qt; PNG is drawn offscreen). Without it, the window starts with these settings and
asks the graph at once. The master is ROS_MASTER_URI's, or `__master:=URI`.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from pathlib import Path

from kame import environ, names
from kame.rqt.graph_model import MODE_BY_OPTION, GraphOptions, build_scene
from kame.rqt.graph_source import NODE_TIMEOUT, GraphSource


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="rqt_graph", description="Show the ROS computation graph.")
    p.add_argument("--mode", choices=sorted(MODE_BY_OPTION), default="nodes",
                   help="nodes: Nodes only; active: Nodes/Topics (active); all: Nodes/Topics (all)")
    p.add_argument("--node-filter", default="", help="comma-separated regular expressions; -x excludes")
    p.add_argument("--topic-filter", default="", help="comma-separated regular expressions; -x excludes")
    p.add_argument("--show-debug", action="store_true", help="show /rosout, rqt's own nodes and the like")
    p.add_argument("--show-dead-sinks", action="store_true", help="show topics nobody subscribes to")
    p.add_argument("--show-leaf-topics", action="store_true", help="show topics only one node uses")
    p.add_argument("--hide-unreachable", action="store_true", help="hide nodes that do not answer")
    p.add_argument("--no-groups", action="store_true", help="do not group by namespace")
    p.add_argument("--group-actions", action="store_true", help="draw each action's five topics as one box")
    p.add_argument("--timeout", type=float, default=NODE_TIMEOUT, help="seconds to wait for each node")
    p.add_argument("-o", "--output", type=Path, help="write the graph to this file (.svg, .dot, .png) and exit")
    return p


def main(argv: Sequence[str] | None = None) -> int:
    ros = names.parse_args(sys.argv[1:] if argv is None else argv)
    args = parser().parse_args(ros.argv)
    options = GraphOptions(mode=MODE_BY_OPTION[args.mode], group_namespaces=not args.no_groups,
                           hide_debug=not args.show_debug, hide_dead_sinks=not args.show_dead_sinks,
                           hide_leaf_topics=not args.show_leaf_topics, hide_unreachable=args.hide_unreachable,
                           node_filter=args.node_filter, topic_filter=args.topic_filter,
                           group_actions=args.group_actions)
    master_uri = environ.master_uri(os.environ, ros.special)
    source = GraphSource(master_uri, node_timeout=args.timeout)
    try:
        if args.output is not None:
            return _write(source, options, args.output)
        return _window(source, options)
    finally:
        source.close()


def _write(source: GraphSource, options: GraphOptions, output: Path) -> int:
    try:
        snapshot = source.fetch()
    except Exception as exc:
        print(f"rqt_graph: cannot reach the master at {source.master_uri}: {exc}", file=sys.stderr)
        return 1
    scene = build_scene(snapshot, options)
    suffix = output.suffix.lower()
    try:
        if suffix in (".svg", ".dot", ".gv"):
            from kame.rqt.graph_export import to_dot, to_svg
            from kame.rqt.graph_layout import layout

            output.write_text(to_dot(scene) if suffix != ".svg" else to_svg(layout(scene)))
        else:
            os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
            from kame.rqt.graph_layout import layout
            from kame.rqt.graph_window import application, graph_font, measure_with, save_drawing

            application()
            font = graph_font()
            save_drawing(output, layout(scene, measure_with(font)), font)
    except OSError as exc:
        print(f"rqt_graph: {exc}", file=sys.stderr)
        return 1
    for name in sorted(snapshot.unreachable):
        print(f"rqt_graph: node {name} did not answer", file=sys.stderr)
    return 0


def _window(source: GraphSource, options: GraphOptions) -> int:
    try:
        from kame.qt_quit import quit_on_signals
        from kame.rqt.graph_window import GraphWindow, application
    except ImportError as exc:
        print(f"rqt_graph needs PySide6 for its window (pip install 'kame[gui]'), or use --output: {exc}",
              file=sys.stderr)
        return 1
    app = application()
    quit_on_signals(app)  # Ctrl-C closes the tool as its window does
    window = GraphWindow(source.fetch, options)
    window.show()
    window.refresh()
    return int(app.exec())


if __name__ == "__main__":
    sys.exit(main())
