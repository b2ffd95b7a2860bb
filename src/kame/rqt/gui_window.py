"""The rqt window: one main window whose Plugins menu opens the rqt tools as dock widgets.

Rules: each plugin instance is a dock (movable, floatable, closable) named by its perspective
key (`rqt_plot#2`), so Qt's saveState/restoreState put it back where it was. Closing a dock
closes its plugin (its node, threads and timers) at once. The perspective (plugins, settings,
dock state, window geometry) is written when the window closes and read when it opens; a
standalone window (`rqt --standalone`) shows one plugin and keeps no perspective. The window
waits for the master (kame.rqt.master_wait, its thread joined on close) and, once it answers,
has every plugin ask again what it could not ask without it.
"""

from __future__ import annotations

import base64
import os
import sys
from pathlib import Path

from PySide6.QtCore import QByteArray, Qt, Signal
from PySide6.QtGui import QAction, QCloseEvent
from PySide6.QtWidgets import QDockWidget, QFrame, QMainWindow, QScrollArea, QWidget

from kame.rqt.master_wait import MasterWaiter
from kame.rqt.perspective import (
    PLUGINS,
    DockedPlugin,
    Perspective,
    PerspectiveError,
    PluginInfo,
    dock_title,
    dumps,
    find_plugin,
    loads,
    menu,
    next_instance,
)
from kame.rqt.plugins import PluginContext, PluginHandle, open_plugin

DOCK_AREAS = (Qt.DockWidgetArea.LeftDockWidgetArea, Qt.DockWidgetArea.RightDockWidgetArea,
              Qt.DockWidgetArea.BottomDockWidgetArea, Qt.DockWidgetArea.TopDockWidgetArea)


DOCK_MINIMUM = (320, 240)  # a dock this small still shows its plugin's controls and some of its view


class PluginDock(QDockWidget):
    closed = Signal(str)  # the perspective key

    def __init__(self, docked: DockedPlugin, title: str, handle: PluginHandle) -> None:
        super().__init__(title)
        self.docked = docked
        self.handle = handle
        self.setObjectName(docked.key)
        self.setFeatures(QDockWidget.DockWidgetFeature.DockWidgetClosable
                         | QDockWidget.DockWidgetFeature.DockWidgetMovable
                         | QDockWidget.DockWidgetFeature.DockWidgetFloatable)
        # the tools' button rows wrap (kame.rqt.flow_layout): the plugin is as wide as its dock,
        # never wider (its right end, Fit and Save, was cut off); it scrolls only up and down
        scroll = QScrollArea()
        scroll.setFrameShape(QFrame.Shape.NoFrame)
        scroll.setWidgetResizable(True)
        scroll.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        scroll.setWidget(handle.widget)
        self.setWidget(scroll)
        self.setMinimumSize(*DOCK_MINIMUM)

    def closeEvent(self, event: QCloseEvent) -> None:
        super().closeEvent(event)
        if event.isAccepted():
            self.closed.emit(self.docked.key)


class RqtWindow(QMainWindow):
    master_up = Signal()

    def __init__(self, context: PluginContext, perspective_file: Path | None = None,
                 plugins: tuple[PluginInfo, ...] = PLUGINS) -> None:
        super().__init__()
        self.setWindowTitle("Default - rqt")  # rqt's title: the perspective, then the program
        self.setObjectName("rqt")
        self.context = context
        self.perspective_file = perspective_file
        self.plugins = plugins
        self.docks: dict[str, PluginDock] = {}
        self.setDockNestingEnabled(True)
        self.setDockOptions(QMainWindow.DockOption.AnimatedDocks | QMainWindow.DockOption.AllowNestedDocks
                            | QMainWindow.DockOption.AllowTabbedDocks)
        centre = QWidget()  # an empty centre: the docks take the room
        self.setCentralWidget(centre)
        centre.hide()
        self.plugin_menu = self.menuBar().addMenu("&Plugins")
        self.plugin_actions: dict[str, QAction] = {}
        for group, entries in menu(plugins).items():
            submenu = self.plugin_menu.addMenu(group)
            for info in entries:
                action = submenu.addAction(info.title)
                action.triggered.connect(lambda _=False, plugin=info.id: self.add_plugin(plugin))
                self.plugin_actions[info.id] = action
        perspectives = self.menuBar().addMenu("P&erspectives")
        perspectives.addAction("Close all plugins").triggered.connect(self.close_all)
        self.resize(1200, 800)
        self.master_up.connect(self._master_is_up)
        self._waiter: MasterWaiter | None = MasterWaiter(context.master_uri, f"/rqt_gui_{os.getpid()}",
                                                         self.master_up.emit)

    def _master_is_up(self) -> None:
        if self._waiter is None:
            return  # closed meanwhile
        self._stop_waiting()
        for dock in list(self.docks.values()):
            dock.handle.master_up()

    def _stop_waiting(self) -> None:
        if self._waiter is not None:
            self._waiter.stop()
            self._waiter = None

    # ---------------------------------------------------------------- plugins

    def docked(self) -> list[DockedPlugin]:
        return [dock.docked for dock in self.docks.values()]

    def add_plugin(self, name: str, instance: int | None = None, settings: dict[str, object] | None = None,
                   area: Qt.DockWidgetArea | None = None) -> PluginDock:
        info = find_plugin(name, self.plugins)
        number = instance if instance is not None else next_instance(self.docked(), info.id)
        docked = DockedPlugin(info.id, number, dict(settings or {}))
        if docked.key in self.docks:
            raise PerspectiveError(f"{docked.key} is open already")
        handle = open_plugin(info, self.context, number, docked.settings)
        dock = PluginDock(docked, dock_title(info, number), handle)
        dock.closed.connect(self._dock_closed)
        self.docks[docked.key] = dock
        self.addDockWidget(area if area is not None else DOCK_AREAS[len(self.docks) % 2], dock)
        return dock

    def _dock_closed(self, key: str) -> None:
        dock = self.docks.pop(key, None)
        if dock is None:
            return
        dock.handle.close()
        self.removeDockWidget(dock)
        dock.deleteLater()

    def close_all(self) -> None:
        for dock in list(self.docks.values()):
            dock.close()

    # ---------------------------------------------------------------- perspective

    def perspective(self) -> Perspective:
        docked = tuple(DockedPlugin(d.docked.plugin, d.docked.instance, d.handle.settings())
                       for d in self.docks.values())
        return Perspective(docked, _text(self.saveGeometry()), _text(self.saveState()))

    def restore(self, perspective: Perspective) -> list[str]:
        """Open the perspective's plugins and put docks and window back; returns the problems."""
        problems = []
        for docked in perspective.plugins:
            try:
                self.add_plugin(docked.plugin, docked.instance, dict(docked.settings))
            except (PerspectiveError, OSError) as exc:
                problems.append(f"{docked.key}: {exc}")
        if perspective.geometry:
            self.restoreGeometry(_bytes(perspective.geometry))
        if perspective.state:
            self.restoreState(_bytes(perspective.state))
        return problems

    def load_perspective(self) -> list[str]:
        if self.perspective_file is None or not self.perspective_file.exists():
            return []
        try:
            return self.restore(loads(self.perspective_file.read_text()))
        except (OSError, PerspectiveError) as exc:
            return [f"{self.perspective_file}: {exc}"]

    def save_perspective(self) -> None:
        if self.perspective_file is None:
            return
        self.perspective_file.parent.mkdir(parents=True, exist_ok=True)
        self.perspective_file.write_text(dumps(self.perspective()))

    def closeEvent(self, event: QCloseEvent) -> None:
        self._stop_waiting()
        try:
            self.save_perspective()
        except OSError as exc:  # the plugins still close; the next run starts from the old perspective
            print(f"rqt: cannot save the perspective: {exc}", file=sys.stderr)
        for dock in list(self.docks.values()):
            dock.handle.close()
        self.docks.clear()
        super().closeEvent(event)


def _text(data: QByteArray) -> str:
    return base64.b64encode(bytes(data.data())).decode("ascii")


def _bytes(text: str) -> QByteArray:
    return QByteArray(base64.b64decode(text.encode("ascii")))
