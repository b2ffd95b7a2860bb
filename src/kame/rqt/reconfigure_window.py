"""rqt_reconfigure's window: pick a dynamic_reconfigure server, see its parameters by group with
their ranges or choices, edit a value (sent through the server's set_parameters), and watch
values change as the server publishes parameter_updates (whoever changed them).

Rules: the source calls `changed` from its subscription's thread; the window redraws on its own
thread (a queued signal). Setting a value runs on the window's worker (kame.rqt.asking); a value
the model refuses is said in the status line and the cell goes back to the server's value.
"""

from __future__ import annotations

from typing import Any

from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import QComboBox, QHBoxLayout, QLabel, QPushButton, QTreeWidget, QTreeWidgetItem, QVBoxLayout

from kame.node.master_proxy import MasterError
from kame.rqt.asking import AskingWindow
from kame.rqt.reconfigure_model import EditError, ParamRow, parse, rows, shown, values
from kame.rqt.reconfigure_source import ReconfigureError, ReconfigureSource

NAME, VALUE, TYPE, RANGE, DESCRIPTION = range(5)


class ReconfigureWindow(AskingWindow):
    failures = (ReconfigureError, OSError, MasterError)
    server_changed = Signal(str)

    def __init__(self, source: ReconfigureSource) -> None:
        super().__init__("rqt-reconfigure")
        self.setWindowTitle("rqt_reconfigure")
        self.source = source
        self.server_box = QComboBox()
        self.server_box.setMinimumContentsLength(30)
        self.refresh_button = QPushButton("Refresh")
        self.tree = QTreeWidget()
        self.tree.setHeaderLabels(("Parameter", "Value", "Type", "Range", "Description"))
        self.tree.setColumnWidth(NAME, 200)
        self.tree.setColumnWidth(VALUE, 160)
        self.rows: dict[str, ParamRow] = {}
        self.items: dict[str, QTreeWidgetItem] = {}
        self._described: dict[str, Any] | None = None
        top = QHBoxLayout()
        for widget in (QLabel("Server"), self.server_box, self.refresh_button):
            top.addWidget(widget)
        top.addStretch(1)
        page = QVBoxLayout(self)
        page.addLayout(top)
        page.addWidget(self.tree, 1)
        page.addWidget(self.status)
        self.resize(820, 520)
        self.refresh_button.clicked.connect(self.refresh_servers)
        self.server_box.currentTextChanged.connect(self.choose)
        self.server_changed.connect(self._redraw)
        self.tree.itemChanged.connect(self._edited)

    def refresh_servers(self) -> None:
        def show(found: list[str]) -> None:
            current = self.server_box.currentText()
            self.server_box.blockSignals(True)
            self.server_box.clear()
            self.server_box.addItems(found)
            self.server_box.setCurrentIndex(found.index(current) if current in found else -1)
            self.server_box.blockSignals(False)
            self.status.setText(f"{len(found)} servers")

        self._ask("asking the master", self.source.servers, show)

    def choose(self, server: str) -> None:
        """Follow `server` (the text of the box; also callable from a perspective or a test)."""
        if self.server_box.currentText() != server:
            self.server_box.blockSignals(True)
            self.server_box.setCurrentText(server)
            self.server_box.blockSignals(False)
        self.tree.clear()
        self.rows, self.items, self._described = {}, {}, None
        if not server:
            self.source.stop()
            return
        self._ask(f"following {server}", lambda: self.source.follow(server), lambda _none: None)

    def _redraw(self, server: str, say: bool = True) -> None:
        if server != self.source.server:
            return
        description, config = self.source.state()
        self.tree.blockSignals(True)
        try:
            if description is not None and description is not self._described:
                self._build(description)
            if config is not None:
                for name, text in values(self.rows.values(), config).items():
                    self.items[name].setText(VALUE, text)
        finally:
            self.tree.blockSignals(False)
        if config is not None and say:
            self.status.setText(f"{server}: {len(self.rows)} parameters")

    def _build(self, description: dict[str, Any]) -> None:
        self._described = description
        self.tree.clear()
        self.rows, self.items = {}, {}
        groups: dict[str, QTreeWidgetItem] = {}
        for row in rows(description):
            parent = self.tree.invisibleRootItem()
            path = ""
            for part in row.group.split("/") if row.group else []:
                path = f"{path}/{part}" if path else part
                if path not in groups:
                    groups[path] = QTreeWidgetItem(parent, [part])
                parent = groups[path]
            item = QTreeWidgetItem(parent, [row.name, "", row.type, row.range_text(), row.description])
            item.setFlags(item.flags() | Qt.ItemFlag.ItemIsEditable)
            self.rows[row.name], self.items[row.name] = row, item
        self.tree.expandAll()

    def set_value(self, name: str, text: str) -> None:
        """Type `text` into parameter `name`'s cell, as a user does."""
        self.items[name].setText(VALUE, text)

    def _edited(self, item: QTreeWidgetItem, column: int) -> None:
        name = item.text(NAME)
        if column != VALUE or name not in self.rows or self.items.get(name) is not item:
            return
        try:
            value = parse(self.rows[name], item.text(VALUE))
        except EditError as exc:
            self.status.setText(str(exc))
            self._redraw(self.source.server, say=False)
            return

        def show(config: dict[str, Any]) -> None:
            self.status.setText(f"{name} set to {shown(self.rows[name], config.get(name, value))}"
                                if name in self.rows else "")

        self._ask(f"setting {name}", lambda: self.source.set({name: value}), show)
