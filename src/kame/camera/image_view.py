"""image_view's image_view: `rosrun image_view image_view image:=/usb_cam/image_raw [transport]`,
a window showing the topic's images (parameters window_name, autosize, filename_format,
image_transport), saving the shown one on a right click (or the `s` key).

The node is kame.client's; the window's loop is the main thread's, ended by closing the window,
Ctrl-C or the node's shutdown."""

from __future__ import annotations

import sys
from collections.abc import Sequence

import numpy as np

from kame.camera.image_feed import ImageFeed, image_topic, transport_argument
from kame.camera.opencv import OpenCVMissing, cv2_for
from kame.camera.viewer_model import ViewerModel, ViewerSettings
from kame.client import core, log
from kame.client.process import get_param, init_node, myargv


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    try:
        cv2 = cv2_for("image_view")
        from PySide6.QtCore import QMetaObject, Qt
        from PySide6.QtWidgets import QApplication

        from kame.camera.image_view_window import ImageViewWindow
        from kame.qt_quit import quit_on_signals
    except OpenCVMissing as exc:
        sys.stderr.write(f"{exc}\n")
        return 1
    except ImportError as exc:
        sys.stderr.write(f"image_view's window needs PySide6: pip install 'kame[gui]' ({exc})\n")
        return 1
    init_node("image_view", argv, anonymous=True)
    args = myargv(argv)
    topic = image_topic("image_view")
    transport = transport_argument(args)
    model = ViewerModel(ViewerSettings(topic, str(get_param("~window_name", "")), bool(get_param("~autosize", False)),
                                       str(get_param("~filename_format", "frame%04i.jpg"))))
    app = QApplication.instance() or QApplication(["image_view"])
    quit_on_signals(app)

    def save() -> None:
        name = model.next_filename()
        if name is None or model.picture is None:
            log.emit(log.WARN, "Couldn't save image, no data!", ())
            return
        if cv2.imwrite(name, model.picture):
            log.emit(log.INFO, "Saved image %s", (name,))
        else:
            log.emit(log.ERROR, "Could not save image %s (does its folder exist?)", (name,))

    def take() -> np.ndarray | None:
        picture = feed.take()
        if picture is not None:
            model.show(picture)
        return picture

    window = ImageViewWindow(model, take, save, lambda text: log.emit(log.WARN, "%s", (text,)))
    try:
        feed = ImageFeed(topic, transport, window.frame_ready.emit)
    except ValueError as exc:
        log.emit(log.FATAL, "%s", (exc,))
        return 1
    core.on_shutdown(lambda *_: QMetaObject.invokeMethod(app, "quit", Qt.ConnectionType.QueuedConnection))
    window.show()
    with core.main_thread_waiting():
        app.exec()
    core.signal_shutdown("image_view closed")
    return 0
