"""rqt_topic, rqt_publisher, rqt_service_caller and rqt_image_view on a live turtlesim, each
through its window (offscreen)."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from typing import Any

import pytest

from kame.node.node import Node
from kame.node.topics import serialize_frame
from kame.rqt.ros_node import start_node
from tests.turtlesim.sim import Sim, turtlesim


@pytest.fixture(scope="module")
def sim(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Sim]:
    with turtlesim(tmp_path_factory.mktemp("rqt_plugins")) as (live, _node):
        yield live


@pytest.fixture
def node(sim: Sim) -> Iterator[Node]:
    tool = start_node("plugin_test", {"master": sim.uri}, sim.env)
    yield tool
    tool.shutdown("test over")


def test_topic_monitor_shows_the_pose_its_rate_and_value(sim: Sim, node: Node, qtbot) -> None:  # type: ignore[no-untyped-def]
    from kame.rqt.topic_source import TopicMonitor
    from kame.rqt.topic_window import BANDWIDTH, HZ, TYPE, VALUE, TopicWindow

    monitor = TopicMonitor(node)
    window = TopicWindow(monitor)
    qtbot.addWidget(window)
    window.refresh_topics()
    pose = window.items["/turtle1/pose"]
    assert pose.text(TYPE) == "turtlesim/Pose" and pose.childCount() == 0
    window.set_watched("/turtle1/pose", True)
    assert monitor.watched() == ["/turtle1/pose"]

    def shown() -> bool:
        window.update_values()
        return pose.childCount() == 5 and bool(pose.text(HZ))

    qtbot.waitUntil(shown, timeout=10_000)
    assert [pose.child(i).text(0) for i in range(5)] == ["x", "y", "theta", "linear_velocity", "angular_velocity"]
    assert 0.0 < float(pose.child(0).text(VALUE)) < 11.1
    assert 20.0 < float(pose.text(HZ)) < 200.0  # turtlesim publishes at 62.5 Hz
    assert pose.text(BANDWIDTH).endswith("B/s") and "messages" in pose.text(VALUE)
    pose.setExpanded(True)
    window.update_values()
    assert pose.isExpanded()  # updated in place
    window.set_watched("/turtle1/pose", False)
    assert monitor.watched() == [] and pose.childCount() == 0 and "/turtle1/pose" not in node.subscriptions
    window.close()


def test_message_publisher_sends_expressions_with_the_counter(sim: Sim, node: Node, qtbot) -> None:  # type: ignore[no-untyped-def]
    from kame.rqt.publisher_source import MessagePublisher
    from kame.rqt.publisher_window import PublisherWindow
    from std_msgs.msg import Float64

    listener = start_node("listener", {"master": sim.uri}, sim.env)
    got: list[float] = []
    lock = threading.Lock()

    def deliver(frames: list[memoryview], header: dict[str, str]) -> None:
        with lock:
            got.extend(Float64().deserialize(bytes(f)).data for f in frames)

    try:
        listener.subscribe("/counter", Float64._type, Float64._md5sum, Float64._full_text, deliver)
        window = PublisherWindow(MessagePublisher(node))
        qtbot.addWidget(window)
        window.refresh_topics()
        row = window.add_publisher("/counter", "std_msgs/Float64", 50.0)
        assert row is not None and list(row.fields) == ["data"]
        window.set_field("/counter", "data", "i * 10 + math.floor(0.5)")
        window.set_enabled("/counter", True)
        qtbot.waitUntil(lambda: len(got) >= 5, timeout=10_000)
        window.set_enabled("/counter", False)
        with lock:
            values = list(got)
        # the listener may connect after the first few: what it gets still counts up by one i a message
        assert values[:3] == [values[0], values[0] + 10, values[0] + 20] and values[0] % 10 == 0
        row.item.setText(2, "20")  # the rate, edited in its cell
        row.item.setText(0, "/renamed")  # the topic cannot be
        assert (row.rate, row.item.text(0)) == (20.0, "/counter")
        sent = row.counter
        window.set_field("/counter", "data", "undefined_name")
        assert not window.publish_once("/counter") and "NameError" in window.status.text()
        assert row.counter == sent and row.item.checkState(0).name == "Unchecked"
        assert window.add_publisher("/x", "no_pkg/Nothing", 1.0) is None and "unknown" in window.status.text()
        window.remove_publisher("/counter")
        assert "/counter" not in node.publications
        window.close()
    finally:
        listener.shutdown("test over")


def test_service_caller_spawns_a_turtle(sim: Sim, node: Node, qtbot) -> None:  # type: ignore[no-untyped-def]
    from kame.rqt.service_source import ServiceCaller
    from kame.rqt.service_window import ServiceWindow

    window = ServiceWindow(ServiceCaller(node))
    qtbot.addWidget(window)
    with qtbot.waitSignal(window.idle, timeout=10_000):
        window.refresh_services()
    services = [window.service_box.itemText(i) for i in range(window.service_box.count())]
    assert "/spawn" in services and "/turtle1/set_pen" in services
    with qtbot.waitSignal(window.idle, timeout=10_000):
        window.service_box.setCurrentText("/spawn")
    assert list(window.fields) == ["x", "y", "theta", "name"] and "turtlesim/Spawn" in window.status.text()
    for field, expression in (("x", "2.0"), ("y", "3.0"), ("theta", "math.pi / 2"), ("name", "'rqt_turtle'")):
        window.set_field(field, expression)
    with qtbot.waitSignal(window.idle, timeout=10_000):
        window.call()
    answer = window.response.topLevelItem(0)
    assert (answer.text(0), answer.text(2)) == ("name", "'rqt_turtle'")
    assert sim.pose("rqt_turtle")["x"] == pytest.approx(2.0)
    window.set_field("x", "'not a number'")
    with qtbot.waitSignal(window.idle, timeout=10_000):
        window.call()
    assert "does not fit turtlesim/Spawn" in window.status.text()
    window.close()


def _image(encoding: str, width: int, height: int, data: bytes) -> Any:
    from sensor_msgs.msg import Image

    size = len(data) // (width * height)
    return Image(height=height, width=width, encoding=encoding, step=width * size, data=data)


def test_image_view_shows_raw_and_compressed_images(sim: Sim, node: Node, qtbot) -> None:  # type: ignore[no-untyped-def]
    from PySide6.QtCore import QBuffer, QIODevice
    from PySide6.QtGui import QColor, QImage

    from kame.rqt.image_source import ImageSource
    from kame.rqt.image_window import ImageWindow
    from sensor_msgs.msg import CompressedImage, Image

    camera = start_node("camera", {"master": sim.uri}, sim.env)
    try:
        raw = camera.advertise("/camera/image_raw", Image._type, Image._md5sum, Image._full_text)
        packed = camera.advertise("/camera/image_raw/compressed", CompressedImage._type, CompressedImage._md5sum,
                                  CompressedImage._full_text)
        windows: list[ImageWindow] = []
        source = ImageSource(node, lambda: windows[0].frame_ready.emit())
        window = ImageWindow(source)
        windows.append(window)
        qtbot.addWidget(window)
        window.show()
        window.refresh_topics()
        topics = [window.topic_box.itemText(i) for i in range(window.topic_box.count())]
        assert topics == ["", "/camera/image_raw", "/camera/image_raw/compressed"]  # only image topics

        window.choose("/camera/image_raw")
        blue_bgr = bytes([255, 0, 0]) * (4 * 3)  # bgr8: blue
        def shown_colour(send: Any, wanted: Any) -> None:
            """Send until the picture shown is the one sent (frames sent while waiting for an
            earlier picture may still be on their way)."""
            def shown() -> bool:
                send()
                return window.image is not None and bool(wanted(window.image.pixelColor(1, 1)))

            qtbot.waitUntil(shown, timeout=10_000)

        def is_rgb(red: int, green: int, blue: int) -> Any:
            return lambda c: (c.red(), c.green(), c.blue()) == (red, green, blue)

        shown_colour(lambda: raw.publish_frame(serialize_frame(_image("bgr8", 4, 3, blue_bgr))), is_rgb(0, 0, 255))
        assert window.status.text() == "/camera/image_raw: 4x3"
        depth = bytes([0, 0, 0, 0]) + bytes([0, 0, 128, 63]) * 11  # 32FC1: 0 (unknown) then 1.0 m
        shown_colour(lambda: raw.publish_frame(serialize_frame(_image("32FC1", 4, 3, depth))), is_rgb(255, 255, 255))
        assert window.image is not None and window.image.pixelColor(0, 0).red() == 0

        picture = QImage(6, 4, QImage.Format.Format_RGB888)
        picture.fill(QColor(0, 200, 0))
        buffer = QBuffer()
        buffer.open(QIODevice.OpenModeFlag.WriteOnly)
        assert picture.save(buffer, "PNG")
        png = bytes(buffer.data().data())
        window.choose("/camera/image_raw/compressed")
        shown_colour(lambda: packed.publish_frame(serialize_frame(CompressedImage(format="png", data=png))),
                     is_rgb(0, 200, 0))
        assert window.image is not None and window.image.width() == 6
        buffer = QBuffer()
        buffer.open(QIODevice.OpenModeFlag.WriteOnly)
        picture.fill(QColor(200, 0, 0))
        assert picture.save(buffer, "JPG")
        jpeg = bytes(buffer.data().data())
        shown_colour(lambda: packed.publish_frame(serialize_frame(CompressedImage(format="jpeg", data=jpeg))),
                     lambda c: abs(c.red() - 200) < 8 and c.green() < 8 and c.blue() < 8)  # lossy
        packed.publish_frame(serialize_frame(CompressedImage(format="png", data=b"not a png")))
        qtbot.waitUntil(lambda: "cannot decode" in window.status.text(), timeout=10_000)
        # the last good picture stays (jpegs sent while waiting above may have been shown meanwhile,
        # so the frame count may have grown; all of them came before the bad one)
        assert window.image is not None and abs(window.image.pixelColor(1, 1).red() - 200) < 8
        window.close()
        assert source.topic == "" and "/camera/image_raw/compressed" not in node.subscriptions
    finally:
        camera.shutdown("test over")
