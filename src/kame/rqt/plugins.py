"""The rqt window's plugins: each tool's window, made with what it needs to talk to ROS, and closed
with all it owns.

Rules: every instance owns its node (`/rqt_gui_<tool>_<n>_<pid>`: two instances never share a
subscription, and rqt_graph hides `/rqt*` as rqt's own), sources and threads; `close()` closes
the widget (its own closeEvent stops its timers and joins its workers), then what was made for
it, newest first. `settings()` is what the perspective keeps of it. `master_up()` is called
when the master answers after the window began without one: the plugin asks again what it
could not ask (topic lists, its restored settings).
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
                 settings: Callable[[], dict[str, Any]] | None = None,
                 on_master_up: Callable[[], None] | None = None) -> None:
        self.widget = widget
        self._closers = closers
        self._settings = settings
        self._on_master_up = on_master_up
        self.closed = False

    def master_up(self) -> None:
        if self._on_master_up is not None and not self.closed:
            self._on_master_up()

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
    return PluginHandle(window, [source.close], on_master_up=window.refresh)


def _plot(context: PluginContext, instance: int, settings: Mapping[str, Any]) -> PluginHandle:
    from kame.rqt.plot_source import PlotSource
    from kame.rqt.plot_window import PlotWindow
    from kame.rqt.ros_node import start_node

    node = start_node(f"gui_plot_{instance}", _node_special(context))
    source = PlotSource(node)
    window = PlotWindow(source)

    def ask() -> None:
        for name in settings.get("series", []):
            if name not in window.curves:
                window.add_series(str(name))
        window.refresh_completions()

    ask()
    return PluginHandle(window, [lambda: node.shutdown("plot closed"), source.close],
                        lambda: {"series": list(window.curves)}, ask)


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
    return PluginHandle(window, [levels.close, window.close_worker], on_master_up=window.refresh)


def _topic(context: PluginContext, instance: int, settings: Mapping[str, Any]) -> PluginHandle:
    from kame.rqt.ros_node import start_node
    from kame.rqt.topic_source import TopicMonitor
    from kame.rqt.topic_window import TopicWindow

    node = start_node(f"gui_topic_{instance}", _node_special(context))
    monitor = TopicMonitor(node)
    window = TopicWindow(monitor)

    def ask() -> None:
        window.refresh_topics()
        for topic in settings.get("watched", []):
            if topic in window.items and topic not in monitor.watched():
                window.set_watched(str(topic), True)

    ask()
    return PluginHandle(window, [lambda: node.shutdown("topic monitor closed"), monitor.close],
                        lambda: {"watched": monitor.watched()}, ask)


def _publisher(context: PluginContext, instance: int, settings: Mapping[str, Any]) -> PluginHandle:
    from kame.rqt.publisher_source import MessagePublisher
    from kame.rqt.publisher_window import EXPRESSION, PublisherWindow
    from kame.rqt.ros_node import start_node

    node = start_node(f"gui_publisher_{instance}", _node_special(context))
    publisher = MessagePublisher(node)
    window = PublisherWindow(publisher)
    window.refresh_topics()
    for kept in settings.get("publishers", []):  # restored unticked: nothing is sent until the user says
        window.add_publisher(str(kept.get("topic", "")), str(kept.get("type", "")), float(kept.get("rate", 1.0)),
                             {str(k): str(v) for k, v in dict(kept.get("expressions", {})).items()})

    def settings_now() -> dict[str, Any]:
        return {"publishers": [{"topic": row.topic, "type": window.publisher.classes[row.topic]._type,
                                "rate": float(row.item.text(EXPRESSION) or 0), "expressions": row.expressions()}
                               for row in window.rows.values()]}

    return PluginHandle(window, [lambda: node.shutdown("publisher closed"), publisher.close], settings_now,
                        window.refresh_topics)


def _service_caller(context: PluginContext, instance: int, settings: Mapping[str, Any]) -> PluginHandle:
    from kame.rqt.ros_node import start_node
    from kame.rqt.service_source import ServiceCaller
    from kame.rqt.service_window import ServiceWindow

    node = start_node(f"gui_service_caller_{instance}", _node_special(context))
    window = ServiceWindow(ServiceCaller(node))
    window.refresh_services()
    return PluginHandle(window, [lambda: node.shutdown("service caller closed"), window.close_worker],
                        on_master_up=window.refresh_services)


def _image_view(context: PluginContext, instance: int, settings: Mapping[str, Any]) -> PluginHandle:
    from kame.rqt.image_source import ImageSource
    from kame.rqt.image_window import ImageWindow
    from kame.rqt.ros_node import start_node

    node = start_node(f"gui_image_view_{instance}", _node_special(context))
    holder: list[ImageWindow] = []
    source = ImageSource(node, lambda: holder[0].frame_ready.emit())
    window = ImageWindow(source)
    holder.append(window)

    def ask() -> None:
        window.refresh_topics()
        if settings.get("topic") and not source.topic:
            window.choose(str(settings["topic"]))

    ask()
    return PluginHandle(window, [lambda: node.shutdown("image view closed"), source.stop],
                        lambda: {"topic": source.topic}, ask)


def _reconfigure(context: PluginContext, instance: int, settings: Mapping[str, Any]) -> PluginHandle:
    from kame.rqt.reconfigure_source import ReconfigureSource
    from kame.rqt.reconfigure_window import ReconfigureWindow
    from kame.rqt.ros_node import start_node

    node = start_node(f"gui_reconfigure_{instance}", _node_special(context))
    holder: list[ReconfigureWindow] = []
    source = ReconfigureSource(node, lambda server: holder[0].server_changed.emit(server))
    window = ReconfigureWindow(source)
    holder.append(window)

    def ask() -> None:
        window.refresh_servers()
        if settings.get("server") and not source.server:
            window.choose(str(settings["server"]))

    ask()
    return PluginHandle(window, [lambda: node.shutdown("reconfigure closed"), window.close_worker],
                        lambda: {"server": source.server}, ask)


Factory = Callable[[PluginContext, int, Mapping[str, Any]], PluginHandle]
FACTORIES: dict[str, Factory] = {
    "rqt_graph": _graph,
    "rqt_plot": _plot,
    "rqt_console": _console,
    "rqt_logger_level": _logger_level,
    "rqt_topic": _topic,
    "rqt_publisher": _publisher,
    "rqt_service_caller": _service_caller,
    "rqt_image_view": _image_view,
    "rqt_reconfigure": _reconfigure,
}


def open_plugin(info: PluginInfo, context: PluginContext, instance: int,
                settings: Mapping[str, Any] | None = None) -> PluginHandle:
    return FACTORIES[info.id](context, instance, settings or {})
