"""rqt_publisher's window: choose a topic, its type and a rate, add it; each publisher is a row
with its fields below it, each field an editable Python expression (`i` is the counter, `math`
and `random` are there), as rqt_publisher lays it out.

Rules: a ticked publisher sends at its rate from a QTimer of its own (rate 0: only "Publish
once"); `i` counts the messages it sent. An expression that fails stops that publisher and
says why in the status line, rather than sending a wrong message every tick.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from PySide6.QtCore import Qt, QTimer
from PySide6.QtGui import QCloseEvent
from PySide6.QtWidgets import (
    QComboBox,
    QDoubleSpinBox,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
    QWidget,
)

from kame.node.master_proxy import MasterError
from kame.rqt.message_tree import editable_fields
from kame.rqt.publisher_source import MessagePublisher, PublisherError

COLUMNS = ("Topic / field", "Type", "Rate / expression")
EXPRESSION = 2


@dataclass
class PublisherRow:
    topic: str
    rate: float
    item: QTreeWidgetItem
    timer: QTimer
    fields: dict[str, QTreeWidgetItem] = field(default_factory=dict)
    counter: int = 0

    def expressions(self) -> dict[str, str]:
        return {path: item.text(EXPRESSION) for path, item in self.fields.items()}


class PublisherWindow(QWidget):
    def __init__(self, publisher: MessagePublisher) -> None:
        super().__init__()
        self.setWindowTitle("rqt_publisher")
        self.publisher = publisher
        self.topic_box = QComboBox()
        self.topic_box.setEditable(True)
        self.topic_box.setMinimumContentsLength(20)
        self.type_box = QComboBox()
        self.type_box.setEditable(True)
        self.type_box.setMinimumContentsLength(20)
        self.rate_box = QDoubleSpinBox()
        self.rate_box.setRange(0.0, 1000.0)
        self.rate_box.setValue(1.0)
        self.rate_box.setSuffix(" Hz")
        self.add_button = QPushButton("+")
        self.remove_button = QPushButton("-")
        self.once_button = QPushButton("Publish once")
        self.tree = QTreeWidget()
        self.tree.setHeaderLabels(COLUMNS)
        self.tree.setColumnWidth(0, 260)
        self.tree.setColumnWidth(1, 160)
        self.status = QLabel("")
        self.rows: dict[str, PublisherRow] = {}
        top = QHBoxLayout()
        for widget in (QLabel("Topic"), self.topic_box, QLabel("Type"), self.type_box, QLabel("Freq."), self.rate_box,
                       self.add_button, self.remove_button, self.once_button):
            top.addWidget(widget)
        page = QVBoxLayout(self)
        page.addLayout(top)
        page.addWidget(self.tree, 1)
        page.addWidget(self.status)
        self.resize(900, 500)
        self._types: dict[str, str] = {}
        self.topic_box.currentTextChanged.connect(self._topic_chosen)
        self.add_button.clicked.connect(lambda: self.add_publisher(self.topic_box.currentText(),
                                                                   self.type_box.currentText(), self.rate_box.value()))
        self.remove_button.clicked.connect(self._remove_selected)
        self.once_button.clicked.connect(self._publish_selected)
        self.tree.itemChanged.connect(self._item_changed)

    def refresh_topics(self) -> None:
        try:
            topics = self.publisher.topic_types()
        except (OSError, MasterError) as exc:
            self.status.setText(f"cannot list topics: {exc}")
            return
        self._types = dict(topics)
        text = self.topic_box.currentText()
        self.topic_box.clear()
        self.topic_box.addItems([t for t, _ in topics])
        self.topic_box.setEditText(text)
        self.type_box.clear()
        self.type_box.addItems(sorted(set(self._types.values())))

    def _topic_chosen(self, topic: str) -> None:
        if topic in self._types:
            self.type_box.setEditText(self._types[topic])

    def add_publisher(self, topic: str, type_name: str, rate: float,
                      expressions: dict[str, str] | None = None) -> PublisherRow | None:
        try:
            cls = self.publisher.add(topic, type_name.strip())
        except (PublisherError, OSError, MasterError) as exc:
            self.status.setText(str(exc))
            return None
        topic = self.publisher.node.resolve(topic)
        if topic in self.rows:
            self.status.setText(f"{topic} has a publisher already")
            return None
        self.tree.blockSignals(True)
        item = QTreeWidgetItem([topic, cls._type, f"{rate:g}"])
        item.setFlags(item.flags() | Qt.ItemFlag.ItemIsUserCheckable | Qt.ItemFlag.ItemIsEditable)
        item.setCheckState(0, Qt.CheckState.Unchecked)
        self.tree.addTopLevelItem(item)
        timer = QTimer(self)
        row = PublisherRow(topic, rate, item, timer)
        for path, field_type in editable_fields(cls):
            child = QTreeWidgetItem(item, [path, field_type, (expressions or {}).get(path, "")])
            child.setFlags(child.flags() | Qt.ItemFlag.ItemIsEditable)
            row.fields[path] = child
        item.setExpanded(True)
        self.tree.blockSignals(False)
        timer.timeout.connect(lambda: self.publish_once(topic))
        self.rows[topic] = row
        self.status.setText(f"publishing {topic} ({cls._type}) when ticked")
        return row

    def set_field(self, topic: str, path: str, expression: str) -> None:
        self.rows[topic].fields[path].setText(EXPRESSION, expression)

    def set_enabled(self, topic: str, on: bool) -> None:
        self.rows[topic].item.setCheckState(0, Qt.CheckState.Checked if on else Qt.CheckState.Unchecked)

    def _item_changed(self, item: QTreeWidgetItem, column: int) -> None:
        if item.parent() is not None:
            return
        row = next((r for r in self.rows.values() if r.item is item), None)
        if row is None:
            return
        if column == 0 and item.text(0) != row.topic:  # only the rate is edited here
            self.tree.blockSignals(True)
            item.setText(0, row.topic)
            self.tree.blockSignals(False)
        if column == EXPRESSION:
            try:
                row.rate = max(0.0, float(item.text(EXPRESSION)))
            except ValueError:
                self.status.setText(f"not a rate: {item.text(EXPRESSION)!r}")
        self._apply_timer(row)

    def _apply_timer(self, row: PublisherRow) -> None:
        if row.item.checkState(0) == Qt.CheckState.Checked and row.rate > 0:
            row.timer.start(max(1, round(1000.0 / row.rate)))
        else:
            row.timer.stop()

    def publish_once(self, topic: str) -> bool:
        row = self.rows[topic]
        try:
            self.publisher.publish(topic, row.expressions(), row.counter)
        except PublisherError as exc:
            row.timer.stop()
            self.tree.blockSignals(True)
            row.item.setCheckState(0, Qt.CheckState.Unchecked)
            self.tree.blockSignals(False)
            self.status.setText(f"stopped: {exc}")
            return False
        row.counter += 1
        return True

    def _selected_row(self) -> PublisherRow | None:
        item = self.tree.currentItem()
        while item is not None and item.parent() is not None:
            item = item.parent()
        return self.rows.get(item.text(0)) if item is not None else None

    def _publish_selected(self) -> None:
        row = self._selected_row()
        if row is not None:
            self.publish_once(row.topic)

    def _remove_selected(self) -> None:
        row = self._selected_row()
        if row is not None:
            self.remove_publisher(row.topic)

    def remove_publisher(self, topic: str) -> None:
        row = self.rows.pop(topic, None)
        if row is None:
            return
        row.timer.stop()
        self.tree.takeTopLevelItem(self.tree.indexOfTopLevelItem(row.item))
        self.publisher.remove(topic)

    def closeEvent(self, event: QCloseEvent) -> None:
        for row in self.rows.values():
            row.timer.stop()
        super().closeEvent(event)
