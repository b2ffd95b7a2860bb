"""rqt_plot: numeric fields of topics, plotted against time as they arrive.

    rqt_plot [/topic/field ...] [/topic/field1:field2] [--history SECONDS] [__master:=URI]

Each argument names one or more series (`/turtle1/pose/x:y` is x and y of /turtle1/pose);
more can be added in the window, with completion of the published numeric fields. The tool
runs as node /rqt_plot_<pid> and keeps the last `--history` seconds (60 unless set).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from kame import names
from kame.rqt.plot_model import DEFAULT_HISTORY


def main(argv: Sequence[str] | None = None) -> int:
    ros = names.parse_args(sys.argv[1:] if argv is None else argv)
    parser = argparse.ArgumentParser(prog="rqt_plot", description="Plot numeric topic fields over time.")
    parser.add_argument("series", nargs="*", help="/topic/field, or /topic/field1:field2")
    parser.add_argument("--history", type=float, default=DEFAULT_HISTORY, help="seconds of data kept and shown")
    args = parser.parse_args(ros.argv)
    if args.history <= 0:
        parser.error("--history must be positive")
    try:
        from kame.qt_quit import quit_on_signals
        from kame.rqt.console_window import application
        from kame.rqt.plot_window import PlotWindow
    except ImportError as exc:
        print(f"rqt_plot needs PySide6 and pyqtgraph (pip install 'kame[gui]'): {exc}", file=sys.stderr)
        return 1
    from kame.rqt.plot_source import PlotSource
    from kame.rqt.ros_node import start_node

    app = application("rqt_plot")
    quit_on_signals(app)  # Ctrl-C closes the tool as its window does
    node = start_node("plot", ros.special)
    source = PlotSource(node, args.history)
    try:
        window = PlotWindow(source)
        for text in args.series:
            window.add_series(text)
        window.refresh_completions()
        window.show()
        return int(app.exec())
    finally:
        node.shutdown("rqt_plot exiting")


if __name__ == "__main__":
    sys.exit(main())
