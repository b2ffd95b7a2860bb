"""rviz's mouse and tools on a live master, offscreen (no drawing needed): a left drag turns the
orbit camera, the wheel zooms, a middle drag pans; 2D Pose Estimate, 2D Nav Goal and Publish
Point publish where the mouse met the ground, facing the drag's direction, in the fixed frame,
stamped with ROS time now (the wall clock, or /clock under /use_sim_time)."""

from __future__ import annotations

import math
import threading
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest

pytest.importorskip("OpenGL", reason="rviz draws through PyOpenGL (pip install 'kame[gui]')")
pytest.importorskip("PySide6")

from PySide6.QtCore import QPoint, Qt
from PySide6.QtTest import QTest

from geometry_msgs.msg import PointStamped, PoseStamped, PoseWithCovarianceStamped
from kame.node.node import Node, NodeConfig
from kame.node.topics import serialize_frame
from kame.rostime import Time
from kame.rviz import config
from kame.rviz.source import RvizSource
from kame.rviz.window import INTERACT, NAV_GOAL, POSE_ESTIMATE, PUBLISH_POINT, RvizWindow
from rosgraph_msgs.msg import Clock
from tests.tf.graph import Graph

SIM_NOW = Time(42, 500_000_000)


def follow_sim_clock(publisher: Node, source: RvizSource) -> None:
    """Publishes SIM_NOW on /clock until rviz's clock reads it (its subscription connects first)."""
    connected = threading.Event()
    clock = publisher.advertise("/clock", Clock._type, Clock._md5sum, Clock._full_text,
                                on_connect=lambda link: connected.set())
    assert connected.wait(10)
    assert source.clock.is_sim_time and source.clock.now() == Time(0, 0)  # roscpp's 0 until the first /clock
    clock.publish_frame(serialize_frame(Clock(SIM_NOW)))
    deadline = time.monotonic() + 10
    while source.clock.now() != SIM_NOW:
        assert time.monotonic() < deadline, "rviz's clock never read /clock"
        time.sleep(0.01)


@pytest.mark.parametrize("sim_time", [False, True], ids=["wall_clock", "sim_time"])
def test_mouse_moves_the_camera_and_the_tools_publish(tmp_path: Path, qtbot: Any, sim_time: bool) -> None:
    graph = Graph(tmp_path)
    rviz = Node(NodeConfig("/rviz_tools_test", graph.uri, "127.0.0.1", "127.0.0.1"))
    listener = Node(NodeConfig("/listener", graph.uri, "127.0.0.1", "127.0.0.1"))
    if sim_time:
        listener.master.call("setParam", "/use_sim_time", True)  # as rviz starts: rospy and roscpp read it then
    source = RvizSource(rviz, lambda: None)
    if sim_time:
        follow_sim_clock(listener, source)
    received: dict[str, Any] = {}
    arrived = threading.Condition()
    connected: dict[str, threading.Event] = {}

    def keep(topic: str, cls: type[Any]) -> None:
        def deliver(frames: list[memoryview], header: dict[str, str]) -> None:
            with arrived:
                received[topic] = cls._from_buffer(frames[-1])
                arrived.notify_all()
        connected[topic] = threading.Event()
        subscription = listener.subscribe(topic, cls._type, cls._md5sum, cls._full_text, deliver)
        subscription.add_connect_callback(lambda _link, topic=topic: connected[topic].set())

    for topic, cls in (("/initialpose", PoseWithCovarianceStamped), ("/move_base_simple/goal", PoseStamped),
                       ("/clicked_point", PointStamped)):
        keep(topic, cls)
    try:
        window = RvizWindow(config.Config(fixed_frame="odom", displays=[]), source)
        qtbot.addWidget(window)
        window.timer.stop()
        window.resize(800, 600)
        window.show()
        qtbot.waitExposed(window)
        qtbot.waitUntil(lambda: window.view.size() == window.view_widget.size())  # laid out: clicks land where aimed
        for topic, event in connected.items():  # rviz's tools advertise their topics as it starts
            assert event.wait(10), f"rviz does not publish {topic}"
        view = window.view
        yaw, distance, focal = view.camera.yaw, view.camera.distance, view.camera.focal_point.copy()
        QTest.mousePress(view, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, QPoint(100, 100))
        QTest.mouseMove(view, QPoint(160, 100))
        QTest.mouseRelease(view, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, QPoint(160, 100))
        assert view.camera.yaw == pytest.approx(yaw - 60 * 0.005)
        QTest.mousePress(view, Qt.MouseButton.MiddleButton, Qt.KeyboardModifier.NoModifier, QPoint(100, 100))
        QTest.mouseMove(view, QPoint(100, 150))
        QTest.mouseRelease(view, Qt.MouseButton.MiddleButton, Qt.KeyboardModifier.NoModifier, QPoint(100, 150))
        assert not np.allclose(view.camera.focal_point, focal)
        view.camera.zoom(1)
        assert view.camera.distance == pytest.approx(distance * 0.9)

        def use(tool: str, start: tuple[float, float], end: tuple[float, float], topic: str) -> Any:
            before = time.time_ns()
            message = published(tool, start, end, topic)
            stamp = message.header.stamp.to_nsec()
            if sim_time:
                assert stamp == SIM_NOW.to_nsec()
            else:  # ros::Time::now() on the wall clock, taken as the tool was used
                assert before <= stamp <= time.time_ns()
            return message

        def published(tool: str, start: tuple[float, float], end: tuple[float, float], topic: str) -> Any:
            window.set_tool(tool)
            with arrived:
                received.pop(topic, None)
            # one use, its first message: the subscriber connected as rviz started
            pixels = [view.camera.project([[*p, 0.0]], view.width(), view.height())[0] for p in (start, end)]
            a, b = (QPoint(round(float(x)), round(float(y))) for x, y in pixels)
            QTest.mousePress(view, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, a)
            QTest.mouseMove(view, b)
            QTest.mouseRelease(view, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, b)
            assert view.tool == INTERACT and window.tool_actions[INTERACT].isChecked()  # the tool is done
            with arrived:
                assert arrived.wait_for(lambda: topic in received, 10), f"nothing on {topic}"
                return received[topic]

        goal = use(NAV_GOAL, (1.0, 1.0), (1.0, 3.0), "/move_base_simple/goal")
        assert goal.header.frame_id == "odom"
        assert (goal.pose.position.x, goal.pose.position.y) == pytest.approx((1.0, 1.0), abs=0.05)
        assert 2 * math.atan2(goal.pose.orientation.z, goal.pose.orientation.w) == pytest.approx(math.pi / 2, abs=0.05)
        estimate = use(POSE_ESTIMATE, (-2.0, 0.5), (-3.0, 0.5), "/initialpose")
        assert (estimate.pose.pose.position.x, estimate.pose.pose.position.y) == pytest.approx((-2, 0.5), abs=0.05)
        assert abs(2 * math.atan2(estimate.pose.pose.orientation.z, estimate.pose.pose.orientation.w)) == \
            pytest.approx(math.pi, abs=0.05)
        assert estimate.pose.covariance[0] == pytest.approx(0.25)
        point = use(PUBLISH_POINT, (0.5, -1.5), (0.5, -1.5), "/clicked_point")
        assert (point.point.x, point.point.y, point.point.z) == pytest.approx((0.5, -1.5, 0.0), abs=0.05)
        window.close()
    finally:
        source.close()
        rviz.shutdown("test over")
        listener.shutdown("test over")
        graph.stop()


def test_measure_and_select_in_the_window(qtbot: Any) -> None:
    """Offscreen there is no OpenGL to read depth from: Measure's clicks meet the ground."""
    from kame.rviz import displays
    from kame.rviz.camera import TOP_DOWN, Camera
    from kame.rviz.window import MEASURE, SELECT
    from tests.rviz.test_colors import cloud_of
    from tests.rviz.test_model import TREE

    cloud = displays.PointCloud2()
    window = RvizWindow(config.Config(fixed_frame="map", camera=Camera(kind=TOP_DOWN, scale=50.0),
                                      displays=[cloud]), None)
    qtbot.addWidget(window)
    window.timer.stop()
    window.resize(800, 600)
    window.show()
    view = window.view
    cloud.receive([cloud_of(x=[0, 2], y=[0, 0], z=[0, 0], intensity=[1, 2])], 0.0)  # map x 1 and 3
    window.draw(0.0, TREE)

    def at(x: float, y: float) -> QPoint:
        px, py = view.camera.project([[x, y, 0.0]], view.width(), view.height())[0]
        return QPoint(round(float(px)), round(float(py)))

    window.set_tool(MEASURE)
    assert window.statusBar().currentMessage().startswith("[Left-Click] Select start point")
    QTest.mouseClick(view, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, at(0.0, 0.0))
    QTest.mouseClick(view, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, at(3.0, 4.0))
    assert window.measure.length == pytest.approx(5.0, abs=0.05)
    assert "length: 5.0" in window.statusBar().currentMessage()
    assert any(b is window.measure.overlay.batches[0] for b in view.scene.batches)  # the line is drawn
    QTest.mouseClick(view, Qt.MouseButton.RightButton, Qt.KeyboardModifier.NoModifier, at(3.0, 4.0))
    assert window.measure.start is None and window.measure.overlay.batches == []

    window.set_tool(SELECT)
    assert window.selection_dock.isVisible()
    yaw = view.camera.yaw
    QTest.mousePress(view, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, at(0.5, 0.5))
    QTest.mouseMove(view, at(2.0, -0.5))
    QTest.mouseRelease(view, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, at(2.0, -0.5))
    assert view.camera.yaw == yaw  # a drag selects, it does not turn the view
    tree = window.selected_tree
    assert tree.topLevelItemCount() == 1 and tree.topLevelItem(0).text(0) == "Point 0"
    shown = {tree.topLevelItem(0).child(i).text(0): tree.topLevelItem(0).child(i).text(1)
             for i in range(tree.topLevelItem(0).childCount())}
    assert shown == {"Position": "1; 0; 0", "intensity": "1"}
    assert any(b is window.selection.overlay.batches[0] for b in view.scene.batches)  # the point is marked
    window.close()


def test_add_a_display_by_topic(tmp_path: Path, qtbot: Any) -> None:
    """Add > By topic offers each published topic a display shows; choosing one adds and subscribes it."""
    from sensor_msgs.msg import LaserScan
    from visualization_msgs.msg import MarkerArray

    graph = Graph(tmp_path)
    rviz = Node(NodeConfig("/rviz_by_topic_test", graph.uri, "127.0.0.1", "127.0.0.1"))
    talker = Node(NodeConfig("/talker", graph.uri, "127.0.0.1", "127.0.0.1"))
    source = RvizSource(rviz, lambda: None)
    try:
        for topic, cls in (("/scan", LaserScan), ("/boxes", MarkerArray), ("/chatter", PointStamped)):
            talker.advertise(topic, cls._type, cls._md5sum, cls._full_text)
        window = RvizWindow(config.Config(fixed_frame="odom", displays=[]), source)
        qtbot.addWidget(window)
        window.timer.stop()
        window.by_topic.aboutToShow.emit()
        offered = [action.text() for action in window.by_topic.actions()]
        assert "/scan (rviz/LaserScan)" in offered and "/boxes (rviz/MarkerArray)" in offered
        assert "/chatter (rviz/PointStamped)" in offered and not any("/rosout" in text for text in offered)
        next(a for a in window.by_topic.actions() if a.text() == "/boxes (rviz/MarkerArray)").trigger()
        added = window.config.displays[-1]
        assert (added.class_name, added.name, added.options["Marker Topic"]) == ("rviz/MarkerArray", "/boxes", "/boxes")
        assert "/boxes" in source.watched()
        window.close()
    finally:
        source.close()
        rviz.shutdown("test over")
        talker.shutdown("test over")
        graph.stop()
