"""rqt_topic's window: every published topic with its type; ticking one subscribes to it and shows
its bandwidth, rate and newest value as an expandable tree (message_tree rows).

Rules: the numbers and values are redrawn once a second (REFRESH_MS) from the monitor; tree
items are updated in place, so what the user expanded stays expanded. Listing the topics asks
the master (Refresh, and when the window opens).
"""

from __future__ import annotations

from PySide6.QtCore import Qt, QTimer
from PySide6.QtGui import QCloseEvent
from PySide6.QtWidgets import QHBoxLayout, QLabel, QPushButton, QTreeWidget, QTreeWidgetItem, QVBoxLayout, QWidget

from kame.node.master_proxy import MasterError
from kame.rqt.message_tree import TreeRow, value_tree
from kame.rqt.topic_model import bandwidth_text, rate_text
from kame.rqt.topic_source import TopicMonitor

REFRESH_MS = 1000
COLUMNS = ("Topic", "Type", "Bandwidth", "Hz", "Value")
TYPE, BANDWIDTH, HZ, VALUE = 1, 2, 3, 4


class TopicWindow(QWidget):
    def __init__(self, monitor: TopicMonitor) -> None:
        super().__init__()
        self.setWindowTitle("rqt_topic")
        self.monitor = monitor
        self.tree = QTreeWidget()
        self.tree.setHeaderLabels(COLUMNS)
        self.tree.setColumnWidth(0, 260)
        self.tree.setColumnWidth(1, 200)
        self.refresh_button = QPushButton("Refresh")
        self.status = QLabel("")
        self.items: dict[str, QTreeWidgetItem] = {}
        bottom = QHBoxLayout()
        bottom.addWidget(self.refresh_button)
        bottom.addWidget(self.status, 1)
        page = QVBoxLayout(self)
        page.addWidget(self.tree, 1)
        page.addLayout(bottom)
        self.resize(900, 500)
        self.refresh_button.clicked.connect(self.refresh_topics)
        self.tree.itemChanged.connect(self._item_changed)
        self.timer = QTimer(self)
        self.timer.timeout.connect(self.update_values)
        self.timer.start(REFRESH_MS)

    def refresh_topics(self) -> None:
        try:
            topics = self.monitor.topics()
        except (OSError, MasterError) as exc:
            self.status.setText(f"cannot list topics: {exc}")
            return
        self.tree.blockSignals(True)
        for topic, type_name in topics:
            item = self.items.get(topic)
            if item is None:
                item = QTreeWidgetItem([topic, type_name])
                item.setFlags(item.flags() | Qt.ItemFlag.ItemIsUserCheckable)
                item.setCheckState(0, Qt.CheckState.Unchecked)
                self.items[topic] = item
                self.tree.addTopLevelItem(item)
            item.setText(TYPE, type_name)
        self.tree.sortItems(0, Qt.SortOrder.AscendingOrder)
        self.tree.blockSignals(False)
        self.status.setText(f"{len(topics)} topics")

    def set_watched(self, topic: str, on: bool) -> None:
        """What ticking the topic's box does."""
        self.items[topic].setCheckState(0, Qt.CheckState.Checked if on else Qt.CheckState.Unchecked)

    def _item_changed(self, item: QTreeWidgetItem, column: int) -> None:
        if column != 0 or item.parent() is not None:
            return
        topic = item.text(0)
        if item.checkState(0) == Qt.CheckState.Checked:
            try:
                self.monitor.watch(topic, item.text(TYPE))
            except (OSError, MasterError, ValueError) as exc:
                self.status.setText(f"cannot subscribe to {topic}: {exc}")
        else:
            self.monitor.unwatch(topic)
            self.tree.blockSignals(True)
            item.takeChildren()
            for column_index in (BANDWIDTH, HZ, VALUE):
                item.setText(column_index, "")
            self.tree.blockSignals(False)

    def update_values(self) -> None:
        self.tree.blockSignals(True)
        try:
            for topic in self.monitor.watched():
                item = self.items.get(topic)
                if item is None:
                    continue
                rate, bandwidth, count = self.monitor.stats(topic)
                item.setText(BANDWIDTH, bandwidth_text(bandwidth))
                item.setText(HZ, rate_text(rate))
                try:
                    message = self.monitor.newest(topic)
                except Exception as exc:  # the publisher's fault: say so in the row, keep going
                    item.setText(VALUE, f"cannot decode: {exc}")
                    continue
                if message is not None:
                    item.setText(VALUE, f"{count} messages")
                    _sync(item, value_tree(message).children)
        finally:
            self.tree.blockSignals(False)

    def closeEvent(self, event: QCloseEvent) -> None:
        self.timer.stop()
        super().closeEvent(event)


def _sync(item: QTreeWidgetItem, rows: tuple[TreeRow, ...]) -> None:
    """Make `item`'s children show `rows`, reusing the items that are there."""
    while item.childCount() > len(rows):
        item.takeChild(item.childCount() - 1)
    for index, row in enumerate(rows):
        child = item.child(index) if index < item.childCount() else None
        if child is None:
            child = QTreeWidgetItem(item)
        child.setText(0, row.name)
        child.setText(TYPE, row.type)
        child.setText(VALUE, row.value)
        _sync(child, row.children)
