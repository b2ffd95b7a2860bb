"""The rqt window's plugins: each tool's window, made with what it needs to talk to ROS, and closed
with all it owns.

Rules: every instance owns its node (`/rqt_gui_<tool>_<n>_<pid>`: two instances never share a
subscription, and rqt_graph hides `/rqt*` as rqt's own), sources and threads; `close()` closes
the widget (its own closeEvent stops its timers and joins its workers), then what was made for
it, newest first. `settings()` is what the perspective keeps of it.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from PySide6.QtWidgets import QWidget

from kame.rqt.perspective import PluginInfo


@dataclass(frozen=True)
class PluginContext:
    master_uri: str
    special: Mapping[str, str] = field(default_factory=dict)  # __master, __ip, __hostname


class PluginHandle:
    def __init__(self, widget: QWidget, closers: list[Callable[[], None]],
                 settings: Callable[[], dict[str, Any]] | None = None) -> None:
        self.widget = widget
        self._closers = closers
        self._settings = settings
        self.closed = False

    def settings(self) -> dict[str, Any]:
        return self._settings() if self._settings is not None else {}

    def close(self) -> None:
        if self.closed:
            return
        self.closed = True
        self.widget.close()
        for closer in reversed(self._closers):
            closer()


def _node_special(context: PluginContext) -> dict[str, str]:
    return dict(context.special, master=context.master_uri)


def _graph(context: PluginContext, instance: int, settings: Mapping[str, Any]) -> PluginHandle:
    from kame.rqt.graph_source import GraphSource
    from kame.rqt.graph_window import GraphWindow

    source = GraphSource(context.master_uri, caller_id=f"/rqt_gui_graph_{instance}_{os.getpid()}")
    window = GraphWindow(source.fetch)
    window.refresh()
    return PluginHandle(window, [source.close])


def _plot(context: PluginContext, instance: int, settings: Mapping[str, Any]) -> PluginHandle:
    from kame.rqt.plot_source import PlotSource
    from kame.rqt.plot_window import PlotWindow
    from kame.rqt.ros_node import start_node

    node = start_node(f"gui_plot_{instance}", _node_special(context))
    source = PlotSource(node)
    window = PlotWindow(source)
    for name in settings.get("series", []):
        window.add_series(str(name))
    window.refresh_completions()
    return PluginHandle(window, [lambda: node.shutdown("plot closed"), source.close],
                        lambda: {"series": list(window.curves)})


def _console(context: PluginContext, instance: int, settings: Mapping[str, Any]) -> PluginHandle:
    from kame.rqt.console_model import LogView
    from kame.rqt.console_window import ConsoleWindow
    from kame.rqt.ros_node import start_node

    node = start_node(f"gui_console_{instance}", _node_special(context))
    window = ConsoleWindow(LogView())
    window.listen(node)
    return PluginHandle(window, [lambda: node.shutdown("console closed"), window.stop_waiting])


def _logger_level(context: PluginContext, instance: int, settings: Mapping[str, Any]) -> PluginHandle:
    from kame.rqt.logger_source import LoggerLevels
    from kame.rqt.logger_window import LoggerWindow

    levels = LoggerLevels(context.master_uri, f"/rqt_gui_logger_level_{instance}_{os.getpid()}")
    window = LoggerWindow(levels)
    window.refresh()
    return PluginHandle(window, [levels.close, window.close_worker])


Factory = Callable[[PluginContext, int, Mapping[str, Any]], PluginHandle]
FACTORIES: dict[str, Factory] = {
    "rqt_graph": _graph,
    "rqt_plot": _plot,
    "rqt_console": _console,
    "rqt_logger_level": _logger_level,
}


def open_plugin(info: PluginInfo, context: PluginContext, instance: int,
                settings: Mapping[str, Any] | None = None) -> PluginHandle:
    return FACTORIES[info.id](context, instance, settings or {})
