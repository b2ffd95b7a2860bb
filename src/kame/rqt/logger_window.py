"""rqt_logger_level's window (PySide6): nodes, their loggers, and the five levels, as rqt's plugin
lays them out. Choosing a level sets it at once (set_logger_level) and reads the loggers back."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QHBoxLayout, QLabel, QListWidget, QListWidgetItem, QPushButton, QVBoxLayout, QWidget

from kame.rqt.logger_source import LEVELS, LoggerError, LoggerLevels


def _column(title: str, widget: QWidget) -> QVBoxLayout:
    column = QVBoxLayout()
    column.addWidget(QLabel(title))
    column.addWidget(widget, 1)
    return column


class LoggerWindow(QWidget):
    def __init__(self, levels: LoggerLevels) -> None:
        super().__init__()
        self.setWindowTitle("rqt_logger_level")
        self.levels = levels
        self.node_list = QListWidget()
        self.logger_list = QListWidget()
        self.level_list = QListWidget()
        for level in LEVELS:
            self.level_list.addItem(QListWidgetItem(level.capitalize()))
        self.refresh_button = QPushButton("Refresh")
        self.status = QLabel("")
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

    def refresh(self) -> None:
        current = self.node_list.currentItem()
        keep = current.text() if current is not None else ""
        self.node_list.clear()
        try:
            nodes = self.levels.nodes()
        except LoggerError as exc:
            self.status.setText(str(exc))
            return
        self.node_list.addItems(nodes)
        self.status.setText(f"{len(nodes)} nodes with logger services")
        if keep in nodes:
            self.node_list.setCurrentRow(nodes.index(keep))

    def show_loggers(self, node: str) -> None:
        self.logger_list.clear()
        self.level_list.clearSelection()
        self._loggers = {}
        if not node:
            return
        try:
            self._loggers = dict(self.levels.loggers(node))
        except LoggerError as exc:
            self.status.setText(str(exc))
            return
        self.logger_list.addItems(sorted(self._loggers))

    def _show_level(self, logger: str) -> None:
        level = self._loggers.get(logger)
        if level in LEVELS:
            self.level_list.setCurrentRow(LEVELS.index(level))
        else:
            self.level_list.clearSelection()

    def choose_level(self, level: str) -> None:
        node, logger = self.node_list.currentItem(), self.logger_list.currentItem()
        if node is None or logger is None:
            self.status.setText("choose a node and a logger first")
            return
        try:
            self.levels.set_level(node.text(), logger.text(), level)
        except LoggerError as exc:
            self.status.setText(str(exc))
            return
        self.status.setText(f"{node.text()}: {logger.text()} set to {level}")
        name = logger.text()
        self.show_loggers(node.text())
        matches = self.logger_list.findItems(name, Qt.MatchFlag.MatchExactly)
        if matches:
            self.logger_list.setCurrentItem(matches[0])
