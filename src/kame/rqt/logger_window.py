"""rqt_logger_level's window (PySide6): nodes, their loggers, and the five levels, as rqt's plugin
lays them out. Choosing a level sets it at once (set_logger_level) and reads the loggers back.

Rules: every call to a node runs on the window's one worker thread (kame.rqt.asking); an
answer about a node or logger that is no longer chosen is dropped.
"""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QHBoxLayout, QLabel, QListWidget, QListWidgetItem, QPushButton, QVBoxLayout, QWidget

from kame.rqt.asking import AskingWindow
from kame.rqt.logger_source import LEVELS, LoggerError, LoggerLevels


def _column(title: str, widget: QWidget) -> QVBoxLayout:
    column = QVBoxLayout()
    column.addWidget(QLabel(title))
    column.addWidget(widget, 1)
    return column


class LoggerWindow(AskingWindow):
    failures = (LoggerError,)

    def __init__(self, levels: LoggerLevels) -> None:
        super().__init__("rqt-logger-level")
        self.setWindowTitle("rqt_logger_level")
        self.levels = levels
        self.node_list = QListWidget()
        self.logger_list = QListWidget()
        self.level_list = QListWidget()
        for level in LEVELS:
            self.level_list.addItem(QListWidgetItem(level.capitalize()))
        self.refresh_button = QPushButton("Refresh")
        self._loggers: dict[str, str] = {}
        lists = QHBoxLayout()
        lists.addLayout(_column("Nodes", self.node_list), 2)
        lists.addLayout(_column("Loggers", self.logger_list), 2)
        lists.addLayout(_column("Levels", self.level_list), 1)
        layout = QVBoxLayout(self)
        layout.addLayout(lists, 1)
        bottom = QHBoxLayout()
        bottom.addWidget(self.refresh_button)
        bottom.addWidget(self.status, 1)
        layout.addLayout(bottom)
        self.resize(760, 420)
        self.refresh_button.clicked.connect(self.refresh)
        self.node_list.currentTextChanged.connect(self.show_loggers)
        self.logger_list.currentTextChanged.connect(self._show_level)
        self.level_list.itemClicked.connect(lambda item: self.choose_level(item.text().lower()))

    # ---------------------------------------------------------------- what the user does

    def refresh(self) -> None:
        self._ask("the master", self.levels.nodes, self._show_nodes)

    def _show_nodes(self, nodes: list[str]) -> None:
        current = self.node_list.currentItem()
        keep = current.text() if current is not None else ""
        self.node_list.blockSignals(True)  # the same node stays chosen: no need to ask it again
        self.node_list.clear()
        self.node_list.addItems(nodes)
        if keep in nodes:
            self.node_list.setCurrentRow(nodes.index(keep))
        self.node_list.blockSignals(False)
        self.status.setText(f"{len(nodes)} nodes with logger services")
        if keep and keep not in nodes:
            self.show_loggers("")

    def _chosen(self, widget: QListWidget) -> str:
        item = widget.currentItem()
        return item.text() if item is not None else ""

    def show_loggers(self, node: str, select: str = "", message: str = "") -> None:
        self.logger_list.clear()
        self.level_list.clearSelection()
        self._loggers = {}
        if not node:
            return

        def show(loggers: list[tuple[str, str]]) -> None:
            if self._chosen(self.node_list) != node:
                return  # the user has moved on
            self._loggers = dict(loggers)
            self.logger_list.clear()
            self.logger_list.addItems(sorted(self._loggers))
            self.status.setText(message or f"{node}: {len(self._loggers)} loggers")
            matches = self.logger_list.findItems(select, Qt.MatchFlag.MatchExactly) if select else []
            if matches:
                self.logger_list.setCurrentItem(matches[0])

        self._ask(f"{node}'s loggers", lambda: self.levels.loggers(node), show)

    def _show_level(self, logger: str) -> None:
        level = self._loggers.get(logger)
        if level in LEVELS:
            self.level_list.setCurrentRow(LEVELS.index(level))
        else:
            self.level_list.clearSelection()

    def choose_level(self, level: str) -> None:
        node, logger = self._chosen(self.node_list), self._chosen(self.logger_list)
        if not node or not logger:
            self.status.setText("choose a node and a logger first")
            return

        def done(_: None) -> None:
            message = f"{node}: {logger} set to {level}"
            self.status.setText(message)
            if self._chosen(self.node_list) == node:
                self.show_loggers(node, select=logger, message=message)

        self._ask(f"{node} to set {logger}", lambda: self.levels.set_level(node, logger, level), done)
