"""rqt_image_view's window: a topic chooser and the newest image, scaled to fit.

Rules: raw images become pixels through image_model (pure); compressed ones are decoded by
Qt's own image readers (jpeg, png). The source wakes the window through `frame_ready` (a
queued signal) and the window takes only the newest frame; a frame that cannot be shown says
why in the status line and the last good one stays.
"""

from __future__ import annotations

from PySide6.QtCore import Qt, Signal
from PySide6.QtGui import QCloseEvent, QImage, QPixmap, QResizeEvent
from PySide6.QtWidgets import QComboBox, QHBoxLayout, QLabel, QPushButton, QSizePolicy, QVBoxLayout, QWidget

from kame.node.master_proxy import MasterError
from kame.rqt.image_model import ImageError, to_display
from kame.rqt.image_source import IMAGE, ImageSource

FORMATS = {1: QImage.Format.Format_Grayscale8, 3: QImage.Format.Format_RGB888, 4: QImage.Format.Format_RGBA8888}


def image_of(type_name: str, data: bytes) -> QImage:
    """A message's bytes as a QImage; ImageError when it cannot be shown."""
    from sensor_msgs.msg import CompressedImage, Image

    if type_name == IMAGE:
        msg = Image().deserialize(data)
        pixels = to_display(msg.encoding, msg.width, msg.height, msg.step, bytes(msg.data), bool(msg.is_bigendian))
        height, width, channels = pixels.shape
        return QImage(pixels.tobytes(), width, height, width * channels, FORMATS[channels]).copy()
    compressed = CompressedImage().deserialize(data)
    image = QImage.fromData(bytes(compressed.data))  # Qt's readers know jpeg and png by their first bytes
    if image.isNull():
        raise ImageError(f"Qt cannot decode this {compressed.format!r} image")
    return image


class ImageWindow(QWidget):
    frame_ready = Signal()

    def __init__(self, source: ImageSource) -> None:
        super().__init__()
        self.setWindowTitle("rqt_image_view")
        self.source = source
        self.topic_box = QComboBox()
        self.topic_box.setMinimumContentsLength(30)
        self.refresh_button = QPushButton("Refresh")
        self.picture = QLabel()
        self.picture.setAlignment(Qt.AlignmentFlag.AlignCenter)
        self.picture.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Ignored)
        self.picture.setMinimumSize(64, 48)
        self.status = QLabel("")
        self.image: QImage | None = None
        self.frames = 0
        top = QHBoxLayout()
        top.addWidget(self.topic_box, 1)
        top.addWidget(self.refresh_button)
        page = QVBoxLayout(self)
        page.addLayout(top)
        page.addWidget(self.picture, 1)
        page.addWidget(self.status)
        self.resize(640, 520)
        self.frame_ready.connect(self.take_frame)
        self.refresh_button.clicked.connect(self.refresh_topics)
        self.topic_box.currentIndexChanged.connect(self._topic_chosen)

    def refresh_topics(self) -> None:
        try:
            topics = self.source.image_topics()
        except (OSError, MasterError) as exc:
            self.status.setText(f"cannot list topics: {exc}")
            return
        current = self.source.topic
        self.topic_box.blockSignals(True)
        self.topic_box.clear()
        self.topic_box.addItem("", "")
        for topic, type_name in topics:
            self.topic_box.addItem(topic, type_name)
        self.topic_box.setCurrentIndex(max(0, self.topic_box.findText(current)) if current else 0)
        self.topic_box.blockSignals(False)

    def choose(self, topic: str) -> None:
        index = self.topic_box.findText(topic)
        if index < 0:
            self.status.setText(f"{topic} is not an image topic")
            return
        self.topic_box.setCurrentIndex(index)

    def _topic_chosen(self, index: int) -> None:
        topic, type_name = self.topic_box.itemText(index), self.topic_box.itemData(index)
        self.image = None
        self.picture.clear()
        if not topic:
            self.source.stop()
            return
        try:
            self.source.show(topic, str(type_name))
        except (OSError, MasterError, ValueError) as exc:
            self.status.setText(f"cannot subscribe to {topic}: {exc}")
            return
        self.status.setText(f"waiting for {topic}")

    def take_frame(self) -> None:
        data = self.source.take()
        if data is None:
            return
        try:
            self.image = image_of(self.source.type_name, data)
        except (ImageError, ValueError) as exc:
            self.status.setText(str(exc))
            return
        except Exception as exc:  # a message that does not deserialize: the publisher's fault
            self.status.setText(f"a message on {self.source.topic} does not deserialize: {exc}")
            return
        self.frames += 1
        self.status.setText(f"{self.source.topic}: {self.image.width()}x{self.image.height()}")
        self._draw()

    def _draw(self) -> None:
        if self.image is not None:
            self.picture.setPixmap(QPixmap.fromImage(self.image).scaled(
                self.picture.size(), Qt.AspectRatioMode.KeepAspectRatio, Qt.TransformationMode.SmoothTransformation))

    def resizeEvent(self, event: QResizeEvent) -> None:
        super().resizeEvent(event)
        self._draw()

    def closeEvent(self, event: QCloseEvent) -> None:
        self.source.stop()
        super().closeEvent(event)
