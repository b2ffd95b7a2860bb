"""rqt_console's window (PySide6): a table over console_model.LogView, its filters and its buttons.

Rules: the table model only reads the LogView; every change goes through the view and comes
back as a console_model.Change, which becomes one row insertion/removal per batch. New
messages arrive through `messages_ready` (a queued signal the feed's thread emits when its
pending list stops being empty) and are taken in one go, at most UPDATES_PER_SECOND times a
second, so a flood costs a few table updates a second, not one per message.
`listen()` subscribes the window's node to the log topic, first waiting for the master (the
status line says so) when it is not up yet, as rqt does.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from PySide6.QtCore import QAbstractTableModel, QModelIndex, QPersistentModelIndex, Qt, QTimer, Signal
from PySide6.QtGui import QBrush, QCloseEvent, QColor, QResizeEvent
from PySide6.QtWidgets import (
    QAbstractItemView,
    QApplication,
    QCheckBox,
    QComboBox,
    QFileDialog,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QLineEdit,
    QPushButton,
    QSpinBox,
    QTableView,
    QVBoxLayout,
    QWidget,
)

from kame.node.master_proxy import MasterError
from kame.node.node import Node
from kame.rqt.console_model import (
    COLUMNS,
    DEBUG,
    ERROR,
    FATAL,
    SEVERITY_NAMES,
    WARN,
    Change,
    Filters,
    FormatError,
    LogEntry,
    LogView,
    Rule,
    dump,
    load,
)
from kame.rqt.console_source import TOPIC, LogFeed
from kame.rqt.flow_layout import FlowLayout
from kame.rqt.master_wait import MasterWaiter

SEVERITY_COLOURS = {DEBUG: QColor("#707070"), WARN: QColor("#b35f00"), ERROR: QColor("#c00000"),
                    FATAL: QColor("#800080")}
HIGHLIGHT = QColor("#fff3a0")
UPDATES_PER_SECOND = 20
Index = QModelIndex | QPersistentModelIndex


class LogTableModel(QAbstractTableModel):
    def __init__(self, view: LogView) -> None:
        super().__init__()
        self.view = view

    def rowCount(self, parent: Index = QModelIndex()) -> int:  # noqa: B008 (Qt's signature)
        return 0 if parent.isValid() else len(self.view)

    def columnCount(self, parent: Index = QModelIndex()) -> int:  # noqa: B008
        return 0 if parent.isValid() else len(COLUMNS)

    def headerData(self, section: int, orientation: Qt.Orientation, role: int = Qt.ItemDataRole.DisplayRole) -> Any:
        if role == Qt.ItemDataRole.DisplayRole and orientation == Qt.Orientation.Horizontal:
            return COLUMNS[section].capitalize()
        return None

    def data(self, index: Index, role: int = Qt.ItemDataRole.DisplayRole) -> Any:
        if not index.isValid():
            return None
        entry = self.view.row(index.row())
        if role == Qt.ItemDataRole.DisplayRole:
            return entry.column(COLUMNS[index.column()])
        if role == Qt.ItemDataRole.ForegroundRole:
            colour = SEVERITY_COLOURS.get(entry.severity)
            return QBrush(colour) if colour is not None else None
        if role == Qt.ItemDataRole.BackgroundRole and self.view.highlighted(index.row()):
            return QBrush(HIGHLIGHT)
        if role == Qt.ItemDataRole.ToolTipRole:
            return entry.message
        return None

    def apply(self, change: Change) -> None:
        """Tell the table what the view's last update did."""
        if change.reset:
            self.beginResetModel()
            self.endResetModel()
            return
        if change.removed:
            self.beginRemoveRows(QModelIndex(), 0, change.removed - 1)
            self.endRemoveRows()
        if change.added:
            first = len(self.view) - change.added
            self.beginInsertRows(QModelIndex(), first, len(self.view) - 1)
            self.endInsertRows()


class RuleEditor(QWidget):
    """One rule: the text, the column it is searched in, regex or plain."""

    changed = Signal()

    def __init__(self, title: str) -> None:
        super().__init__()
        self.text = QLineEdit()
        self.text.setPlaceholderText(title)
        self.column = QComboBox()
        for name in ("message", "node", "topics", "location", "any"):
            self.column.addItem(name)
        self.regex = QCheckBox("Regex")
        row = QHBoxLayout(self)
        row.setContentsMargins(0, 0, 0, 0)
        row.addWidget(self.text, 1)
        row.addWidget(self.column)
        row.addWidget(self.regex)
        self.text.textChanged.connect(self.changed)
        self.column.currentIndexChanged.connect(self.changed)
        self.regex.toggled.connect(self.changed)

    def rules(self) -> tuple[Rule, ...]:
        text = self.text.text()
        return (Rule(text, self.column.currentText(), self.regex.isChecked()),) if text else ()


class _LogTable(QTableView):
    """The messages' table: Message stretches over what the other columns leave. In a narrow
    table (docked beside two other plugins, Message collapsed to an ellipsis) the others give
    way, Location first, then Topics, Stamp and Node, down to NARROWEST, until Message has
    MESSAGE_SHARE of the width and at least MESSAGE_LEAST (at rqt_console's own width only Location
    narrows a little)."""

    COLUMN_WIDTHS = (60, 140, 230, 160, 260)  # severity, node, stamp, topics, location
    NARROWEST = 70
    MESSAGE_SHARE = 0.25
    MESSAGE_LEAST = 160

    def fit_columns(self) -> None:
        width = self.viewport().width()
        room = width - max(self.MESSAGE_LEAST, width * self.MESSAGE_SHARE)
        widths = list(self.COLUMN_WIDTHS)
        for index in (4, 3, 2, 1):
            excess = sum(widths) - room
            if excess <= 0:
                break
            widths[index] = max(self.NARROWEST, int(widths[index] - excess))
        for column, column_width in enumerate(widths, start=1):
            self.setColumnWidth(column, column_width)

    def resizeEvent(self, event: QResizeEvent) -> None:
        super().resizeEvent(event)
        self.fit_columns()


class ConsoleWindow(QWidget):
    messages_ready = Signal()
    master_up = Signal()
    listening = Signal()  # subscribed to the log topic

    def __init__(self, view: LogView, take: Callable[[], list[LogEntry]] | None = None) -> None:
        super().__init__()
        self.setWindowTitle("rqt_console")
        self.view = view
        self.take = take
        self.model = LogTableModel(view)
        self.table = _LogTable()
        self.table.setModel(self.model)
        self.table.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)
        self.table.verticalHeader().setVisible(False)
        self.table.verticalHeader().setDefaultSectionSize(20)
        self.table.horizontalHeader().setSectionResizeMode(0, QHeaderView.ResizeMode.Stretch)
        self.table.fit_columns()
        self.table.setWordWrap(False)

        self.pause_button = QPushButton("Pause")
        self.pause_button.setCheckable(True)
        self.clear_button = QPushButton("Clear")
        self.save_button = QPushButton("Save...")
        self.load_button = QPushButton("Load...")
        self.autoscroll = QCheckBox("Autoscroll")
        self.autoscroll.setChecked(True)
        self.capacity = QSpinBox()
        self.capacity.setRange(100, 10_000_000)
        self.capacity.setSingleStep(1000)
        self.capacity.setValue(view.capacity)
        self.capacity.setPrefix("keep ")
        self.severity_boxes = {level: QCheckBox(name) for level, name in SEVERITY_NAMES.items()}
        for box in self.severity_boxes.values():
            box.setChecked(True)
        self.nodes = QLineEdit()
        self.nodes.setPlaceholderText("nodes (comma-separated; empty: all)")
        self.exclude = RuleEditor("exclude messages matching...")
        self.highlight = RuleEditor("highlight messages matching...")
        self.status = QLabel("")

        # rows that wrap, so a narrow dock keeps every control on screen
        buttons = FlowLayout()
        buttons.add_widgets(self.pause_button, self.clear_button, self.save_button, self.load_button, self.autoscroll,
                            self.capacity, self.status)
        severities = FlowLayout()
        self.nodes.setMinimumWidth(220)
        severities.add_widgets(QLabel("Show:"), *self.severity_boxes.values(), self.nodes)
        page = QVBoxLayout(self)
        page.addWidget(self.table, 1)
        page.addLayout(buttons)
        page.addLayout(severities)
        page.addWidget(self.exclude)
        page.addWidget(self.highlight)
        self.resize(1100, 600)

        self._last_take = 0.0
        self._take_pending = False
        self.connection = ""  # what the status line says about the master while there is none
        self._node: Node | None = None
        self._topic = TOPIC
        self._waiter: MasterWaiter | None = None
        self.master_up.connect(self._subscribe)
        self.messages_ready.connect(self.take_messages)
        self.pause_button.toggled.connect(self.set_paused)
        self.clear_button.clicked.connect(self.clear)
        self.save_button.clicked.connect(self._ask_save)
        self.load_button.clicked.connect(self._ask_load)
        self.capacity.editingFinished.connect(lambda: self._apply(self.view.set_capacity(self.capacity.value())))
        for box in self.severity_boxes.values():
            box.toggled.connect(self.update_filters)
        self.nodes.textChanged.connect(self.update_filters)
        self.exclude.changed.connect(self.update_filters)
        self.highlight.changed.connect(self.update_filters)
        self._show_status()

    def listen(self, node: Node, topic: str = TOPIC) -> None:
        """Show `topic`'s messages, once the node's master answers."""
        self._node, self._topic = node, topic
        self._wait_for_master()

    def _wait_for_master(self) -> None:
        assert self._node is not None
        self.stop_waiting()
        self.connection = f"waiting for the master at {self._node.config.master_uri}"
        self._show_status()
        self._waiter = MasterWaiter(self._node.config.master_uri, self._node.name, self.master_up.emit)

    def _subscribe(self) -> None:
        if self._node is None or self._waiter is None:
            return  # closed meanwhile
        self.stop_waiting()
        try:
            feed = LogFeed(self._node, self.messages_ready.emit, self._topic, self.view.capacity)
        except (OSError, MasterError):  # gone again between its answer and ours
            self._node.unsubscribe(self._topic)  # the node keeps a subscription the master did not take
            self._wait_for_master()
            return
        self.take = feed.take
        self.connection = ""
        self._show_status()
        self.listening.emit()

    def stop_waiting(self) -> None:
        if self._waiter is not None:
            self._waiter.stop()
            self._waiter = None

    def take_messages(self) -> None:
        """Take what arrived, at most UPDATES_PER_SECOND times a second: what comes meanwhile waits
        in the feed (which wakes the window again only once it has been emptied)."""
        if self.take is None or self._take_pending:
            return
        wait = self._last_take + 1.0 / UPDATES_PER_SECOND - time.monotonic()
        if wait > 0:
            self._take_pending = True
            QTimer.singleShot(int(wait * 1000) + 1, self._take_now)
            return
        self._take_now()

    def _take_now(self) -> None:
        self._take_pending = False
        self._last_take = time.monotonic()
        if self.take is not None:
            self.add(self.take())

    def add(self, entries: list[LogEntry]) -> None:
        if entries:
            self._apply(self.view.add(entries))

    def _apply(self, change: Change) -> None:
        self.model.apply(change)
        if change.added and self.autoscroll.isChecked():
            self.table.scrollToBottom()
        self._show_status()

    def _show_status(self) -> None:
        text = self.connection or f"{len(self.view)} of {self.view.stored_count} messages shown"
        if self.view.paused:
            text += " (paused)"
        if self.view.matcher.errors:
            text += "; bad regex " + "; ".join(self.view.matcher.errors)
        self.status.setText(text)

    def filters(self) -> Filters:
        nodes = frozenset(n.strip() for n in self.nodes.text().split(",") if n.strip())
        return Filters(frozenset(level for level, box in self.severity_boxes.items() if box.isChecked()), nodes,
                       self.exclude.rules(), self.highlight.rules())

    def update_filters(self) -> None:
        self._apply(self.view.set_filters(self.filters()))

    def set_paused(self, paused: bool) -> None:
        self.pause_button.setText("Resume" if paused else "Pause")
        self._apply(self.view.set_paused(paused))

    def clear(self) -> None:
        self._apply(self.view.clear())

    def save(self, path: Path) -> None:
        path.write_text(dump(self.view.rows()))

    def load_file(self, path: Path) -> None:
        self.clear()
        self.add(load(path.read_text()))

    def _ask_save(self) -> None:
        name, _ = QFileDialog.getSaveFileName(self, "Save messages", "rosout.csv", "rqt_console (*.csv *.txt)")
        if name:
            try:
                self.save(Path(name))
            except OSError as exc:
                self.status.setText(str(exc))

    def _ask_load(self) -> None:
        name, _ = QFileDialog.getOpenFileName(self, "Load messages", "", "rqt_console (*.csv *.txt)")
        if name:
            try:
                self.load_file(Path(name))
            except (OSError, FormatError) as exc:
                self.status.setText(str(exc))

    def closeEvent(self, event: QCloseEvent) -> None:
        self.stop_waiting()
        self._node = None
        self.take = None
        super().closeEvent(event)


def application(name: str) -> QApplication:
    app = QApplication.instance()
    if isinstance(app, QApplication):
        return app
    return QApplication([name])
