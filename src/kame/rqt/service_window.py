"""rqt_service_caller's window: pick a service, fill its request (one Python expression per
field, `math` and `random` there), call it, read the response as a tree.

Rules: asking a service its type and calling it run on the window's one worker thread (a hung
service shows "calling...", it does not freeze the window: kame.rqt.asking).
"""

from __future__ import annotations

from typing import Any

from PySide6.QtCore import Qt
from PySide6.QtWidgets import (
    QComboBox,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QSplitter,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
)

from kame.node.master_proxy import MasterError
from kame.rqt.asking import AskingWindow
from kame.rqt.message_tree import TreeRow, editable_fields, value_tree
from kame.rqt.service_source import CallError, ServiceCaller

EXPRESSION = 2


class ServiceWindow(AskingWindow):
    failures = (CallError, OSError, MasterError)
    waiting = "{}..."

    def __init__(self, caller: ServiceCaller) -> None:
        super().__init__("rqt-service-caller")
        self.setWindowTitle("rqt_service_caller")
        self.caller = caller
        self.service_box = QComboBox()
        self.service_box.setMinimumContentsLength(30)
        self.refresh_button = QPushButton("Refresh")
        self.call_button = QPushButton("Call")
        self.call_button.setEnabled(False)
        self.request = QTreeWidget()
        self.request.setHeaderLabels(("Request field", "Type", "Expression"))
        self.response = QTreeWidget()
        self.response.setHeaderLabels(("Response field", "Type", "Value"))
        for tree in (self.request, self.response):
            tree.setColumnWidth(0, 220)
        self.service_class: Any = None
        self.fields: dict[str, QTreeWidgetItem] = {}
        top = QHBoxLayout()
        for widget in (QLabel("Service"), self.service_box, self.refresh_button, self.call_button):
            top.addWidget(widget)
        top.addStretch(1)
        split = QSplitter(Qt.Orientation.Vertical)
        split.addWidget(self.request)
        split.addWidget(self.response)
        page = QVBoxLayout(self)
        page.addLayout(top)
        page.addWidget(split, 1)
        page.addWidget(self.status)
        self.resize(800, 520)
        self.refresh_button.clicked.connect(self.refresh_services)
        self.service_box.currentTextChanged.connect(self.choose_service)
        self.call_button.clicked.connect(self.call)

    def refresh_services(self) -> None:
        def show(services: list[str]) -> None:
            current = self.service_box.currentText()
            self.service_box.blockSignals(True)
            self.service_box.clear()
            self.service_box.addItems(services)
            self.service_box.blockSignals(False)
            self.status.setText(f"{len(services)} services")
            if current in services:
                self.service_box.setCurrentText(current)
            elif services and not current:
                self.service_box.setCurrentIndex(-1)

        self._ask("asking the master", self.caller.services, show)

    def choose_service(self, service: str) -> None:
        self.call_button.setEnabled(False)
        self.request.clear()
        self.response.clear()
        self.fields = {}
        self.service_class = None
        if not service:
            return

        def show(cls: Any) -> None:
            if self.service_box.currentText() != service:
                return
            self.service_class = cls
            for path, field_type in editable_fields(cls._request_class):
                item = QTreeWidgetItem(self.request, [path, field_type, ""])
                item.setFlags(item.flags() | Qt.ItemFlag.ItemIsEditable)
                self.fields[path] = item
            self.call_button.setEnabled(True)
            self.status.setText(f"{service}: {cls._type}")

        self._ask(f"asking {service} its type", lambda: self.caller.service_class(service), show)

    def set_field(self, path: str, expression: str) -> None:
        self.fields[path].setText(EXPRESSION, expression)

    def call(self) -> None:
        service, cls = self.service_box.currentText(), self.service_class
        if cls is None:
            return
        expressions = {path: item.text(EXPRESSION) for path, item in self.fields.items()}

        def show(response: Any) -> None:
            self.response.clear()
            _add_rows(self.response.invisibleRootItem(), value_tree(response).children)
            self.response.expandAll()
            self.status.setText(f"{service} answered")

        self._ask(f"calling {service}", lambda: self.caller.call(service, cls, expressions), show)


def _add_rows(parent: QTreeWidgetItem, rows: tuple[TreeRow, ...]) -> None:
    for row in rows:
        _add_rows(QTreeWidgetItem(parent, [row.name, row.type, row.value]), row.children)
