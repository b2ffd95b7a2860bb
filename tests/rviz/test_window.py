"""rviz's window (offscreen: no drawing needed) repaints only when the scene changed: a still
scene, every display reusing its cached batches, is not drawn again at the frame rate."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

pytest.importorskip("OpenGL", reason="rviz's window needs PyOpenGL (pip install 'kame[gui]')")
pytest.importorskip("PySide6")

from geometry_msgs.msg import PointStamped
from kame.rviz import config, displays
from tests.rviz.test_model import TREE, TreeOf


def test_a_still_scene_is_not_repainted(qtbot: Any) -> None:
    from kame.rviz.window import RvizWindow

    point = displays.PointStamped()
    window = RvizWindow(config.Config(fixed_frame="map", displays=[displays.Grid(), point]), None)
    qtbot.addWidget(window)
    window.timer.stop()
    clicked = PointStamped()
    clicked.header.frame_id = "odom"
    point.receive([clicked], 0.0)
    window.draw(0.0, TREE)
    shown = window.view.scene
    assert len(shown.batches) == 2
    window.draw(0.1, TREE)
    assert window.view.scene is shown  # the same batches: nothing to repaint
    window.draw(0.2, TreeOf("map", {"odom": ("map", (5.0, 0.0, 0.0))}))  # odom moved: the point with it
    assert window.view.scene is not shown and window.view.scene.batches[0] is shown.batches[0]


def _window_on(qtbot: Any, display: Any, publish: Any = lambda topic, message: None) -> Any:
    """An offscreen rviz window showing one InteractiveMarkers display, drawn once: its feedback
    goes to `publish`, and tf is the test's (no node)."""
    from kame.rviz.window import RvizWindow
    from tests.rviz.test_interact import Identity

    window = RvizWindow(config.Config(fixed_frame="fixed", displays=[display]), None)
    qtbot.addWidget(window)
    window.timer.stop()
    window.resize(800, 600)
    window.show()  # the view is a native window of its own: laid out (sized) once shown
    qtbot.waitExposed(window)
    window.view.interact.publish = publish
    window.view.interact.redraw = lambda: window.draw(0.0, Identity())
    window.draw(0.0, Identity())
    return window


def test_the_interact_tool_routes_a_drag_and_a_menu_to_the_feedback_topic(qtbot: Any) -> None:
    """The view's mouse on an interactive marker's control (no drawing: the model's geometry):
    a left drag publishes rviz's feedback on <ns>/feedback, a right click opens the marker's
    menu and its entry is sent as MENU_SELECT; a press beside the marker moves the camera."""
    from PySide6.QtCore import QPoint, Qt
    from PySide6.QtTest import QTest
    from PySide6.QtWidgets import QApplication, QMenu

    from kame.rviz.camera import TOP_DOWN
    from tests.rviz.test_interact import Identity, _control, _display_with
    from visualization_msgs.msg import InteractiveMarkerFeedback, MenuEntry

    display = _display_with(_control("move_x", 3, 1, 1, 0, 0))
    display.client.markers[("/basic_controls", "box")].menu_entries = [
        MenuEntry(id=1, parent_id=0, title="Submenu"), MenuEntry(id=2, parent_id=1, title="Inner")]
    sent: list[tuple[str, Any]] = []
    window = _window_on(qtbot, display, lambda topic, message: sent.append((topic, message)))
    window.view.camera.become(TOP_DOWN)
    window.view.camera.scale = 100.0
    window.draw(0.0, Identity())
    view = window.view

    def pixel(x: float, y: float) -> QPoint:
        at = view.camera.project([[x, y, 0.0]], view.width(), view.height())[0]
        return QPoint(round(float(at[0])), round(float(at[1])))

    left, none = Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier
    QTest.mousePress(view, left, none, pixel(0.8, 0.0))
    QTest.mouseMove(view, pixel(1.1, 0.0))
    QTest.mouseRelease(view, left, none, pixel(1.1, 0.0))
    events = [(topic, m.event_type) for topic, m in sent]
    assert events[:2] == [("/basic_controls/feedback", InteractiveMarkerFeedback.POSE_UPDATE),
                          ("/basic_controls/feedback", InteractiveMarkerFeedback.MOUSE_DOWN)]
    assert events[-1] == ("/basic_controls/feedback", InteractiveMarkerFeedback.MOUSE_UP)
    moved = [m for _, m in sent if m.event_type == InteractiveMarkerFeedback.POSE_UPDATE][-1]
    assert abs(moved.pose.position.x - 0.3) < 0.02
    sent.clear()
    QTest.mousePress(view, Qt.MouseButton.RightButton, none, pixel(1.1, 0.0))  # the arrow, moved with the marker
    assert not [w for w in QApplication.topLevelWidgets() if isinstance(w, QMenu) and w.isVisible()]
    QTest.mouseRelease(view, Qt.MouseButton.RightButton, none, pixel(1.1, 0.0))  # rviz opens it on the release
    menus = [w for w in QApplication.topLevelWidgets() if isinstance(w, QMenu) and w.isVisible()]
    assert len(menus) == 1 and [a.text() for a in menus[0].actions()] == ["Submenu"]
    inner = menus[0].actions()[0].menu().actions()[0]
    assert inner.text() == "Inner"
    inner.trigger()
    assert [(m.event_type, m.menu_entry_id) for _, m in sent] == [(InteractiveMarkerFeedback.MENU_SELECT, 2)]
    menus[0].close()
    before = (view.camera.angle, tuple(view.camera.focal_point))
    QTest.mousePress(view, left, none, pixel(-3.0, 2.0))  # nothing there: the camera's
    QTest.mouseMove(view, pixel(-2.0, 2.0))
    QTest.mouseRelease(view, left, none, pixel(-2.0, 2.0))
    assert len(sent) == 1 and (view.camera.angle, tuple(view.camera.focal_point)) != before


def test_the_interact_tool_takes_shift_and_ctrl_from_the_mouse_events(qtbot: Any) -> None:
    """A MOVE_ROTATE_3D box: the wheel turned while it is held moves it along the ray; dragged
    in the view it moves; dragged with Ctrl held, it turns (rviz's Ctrl + left drag) and stays."""
    from PySide6.QtCore import QPoint, QPointF, Qt
    from PySide6.QtGui import QMouseEvent, QWheelEvent
    from PySide6.QtWidgets import QApplication

    from tests.rviz.test_interact import Identity, _display_with
    from tests.rviz.test_interact_3d import _box_control
    from visualization_msgs.msg import InteractiveMarkerControl

    display = _display_with(_box_control(InteractiveMarkerControl.MOVE_ROTATE_3D))
    window = _window_on(qtbot, display)
    view = window.view
    at = view.camera.project([[0.0, 0.0, 0.0]], view.width(), view.height())[0]
    left = Qt.MouseButton.LeftButton

    def send(kind: Any, dx: float, keys: Any) -> None:
        point = QPointF(float(at[0]) + dx, float(at[1]))
        buttons = Qt.MouseButton.NoButton if kind == QMouseEvent.Type.MouseButtonRelease else left
        QApplication.sendEvent(view, QMouseEvent(kind, point, view.mapToGlobal(point), left, buttons, keys))

    def drag(keys: Any) -> None:
        send(QMouseEvent.Type.MouseButtonPress, 0, keys)
        send(QMouseEvent.Type.MouseMove, 75, keys)
        send(QMouseEvent.Type.MouseButtonRelease, 75, keys)

    handle = display.handles[0]
    eye = view.camera.eye()
    send(QMouseEvent.Type.MouseButtonPress, 0, Qt.KeyboardModifier.NoModifier)
    point = QPointF(float(at[0]), float(at[1]))
    QApplication.sendEvent(view, QWheelEvent(point, view.mapToGlobal(point), QPoint(), QPoint(0, 120), left,
                                             Qt.KeyboardModifier.NoModifier, Qt.ScrollPhase.NoScrollPhase, False))
    send(QMouseEvent.Type.MouseButtonRelease, 0, Qt.KeyboardModifier.NoModifier)
    assert float(np.linalg.norm(handle.pose[:3, 3] - eye)) == pytest.approx(float(np.linalg.norm(eye)) + 2)  # away
    handle.marker.pose.position.x = handle.marker.pose.position.y = handle.marker.pose.position.z = 0.0
    window.draw(0.0, Identity())
    handle = display.handles[0]
    drag(Qt.KeyboardModifier.ControlModifier)
    assert handle.pose[:3, 3] == pytest.approx([0, 0, 0], abs=1e-9) and abs(handle.pose[0, 0]) < 0.99
    turned = handle.pose[:3, :3].copy()
    drag(Qt.KeyboardModifier.NoModifier)
    assert float(abs(display.handles[0].pose[:3, 3]).max()) > 0.3
    assert display.handles[0].pose[:3, :3] == pytest.approx(turned)


def test_the_window_turns_view_facing_controls_to_its_camera(qtbot: Any) -> None:
    from kame.rviz.window import RvizWindow
    from tests.rviz.test_interact import Identity, _display_with
    from tests.rviz.test_view_facing import _plate_control
    from visualization_msgs.msg import InteractiveMarkerControl

    display = _display_with(_plate_control(InteractiveMarkerControl.MOVE_PLANE, independent=False))
    window = RvizWindow(config.Config(fixed_frame="fixed", displays=[display]), None)
    qtbot.addWidget(window)
    window.timer.stop()
    for dx in (0, 200):
        window.view.camera.rotate(dx, 0)
        window.draw(0.0, Identity())
        forward = -window.view.camera.view_matrix()[2, :3]
        assert display.handles[0].control_frame()[:3, 0] == pytest.approx(forward)


def test_a_left_click_on_a_menu_control_opens_the_menu_on_the_release(qtbot: Any) -> None:
    from PySide6.QtCore import QPoint, Qt
    from PySide6.QtTest import QTest
    from PySide6.QtWidgets import QApplication, QMenu

    from tests.rviz.test_interact import _display_with
    from tests.rviz.test_interact_3d import _box_control
    from visualization_msgs.msg import InteractiveMarkerControl, InteractiveMarkerFeedback, MenuEntry

    display = _display_with(_box_control(InteractiveMarkerControl.MENU))
    display.client.markers[("/basic_controls", "box")].menu_entries = [MenuEntry(id=1, parent_id=0, title="Reset")]
    sent: list[Any] = []
    window = _window_on(qtbot, display, lambda topic, message: sent.append(message.event_type))
    view = window.view
    at = view.camera.project([[0.0, 0.0, 0.0]], view.width(), view.height())[0]
    centre = QPoint(round(float(at[0])), round(float(at[1])))

    def shown() -> list[QMenu]:
        return [w for w in QApplication.topLevelWidgets() if isinstance(w, QMenu) and w.isVisible()]

    QTest.mousePress(view, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, centre)
    assert not shown() and sent == [InteractiveMarkerFeedback.POSE_UPDATE, InteractiveMarkerFeedback.MOUSE_DOWN]
    QTest.mouseRelease(view, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, centre)
    assert [a.text() for a in shown()[0].actions()] == ["Reset"] and sent[-1] == InteractiveMarkerFeedback.MOUSE_UP
    shown()[0].close()


def test_the_interact_tool_highlights_the_control_under_the_mouse(qtbot: Any) -> None:
    """rviz brightens the control the mouse is over (0.3), more while pressed (0.5), and none
    once the mouse has left it; the view is drawn again each time."""
    from PySide6.QtCore import QPoint, QPointF, Qt
    from PySide6.QtGui import QMouseEvent
    from PySide6.QtTest import QTest
    from PySide6.QtWidgets import QApplication

    from tests.rviz.test_interact import _display_with
    from tests.rviz.test_interact_3d import _box_control
    from visualization_msgs.msg import InteractiveMarkerControl

    display = _display_with(_box_control(InteractiveMarkerControl.BUTTON))
    window = _window_on(qtbot, display)
    view = window.view
    at = view.camera.project([[0.0, 0.0, 0.0]], view.width(), view.height())[0]
    centre = QPoint(round(float(at[0])), round(float(at[1])))

    def hover(point: QPoint) -> None:  # a move with no button down (the view tracks the mouse)
        where = QPointF(point)
        QApplication.sendEvent(view, QMouseEvent(QMouseEvent.Type.MouseMove, where, view.mapToGlobal(where),
                                                 Qt.MouseButton.NoButton, Qt.MouseButton.NoButton,
                                                 Qt.KeyboardModifier.NoModifier))

    def darkest() -> float:
        return float(min(b.float_colors()[:, :3].min() for b in view.scene.batches))

    hover(QPoint(5, 5))
    plain = darkest()
    hover(centre)
    assert display.highlit is not None and display.highlit[3] == 0.3
    assert darkest() == pytest.approx(plain + 0.3)  # drawn again, brighter
    QTest.mousePress(view, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, centre)
    assert display.highlit[3] == 0.5
    QTest.mouseRelease(view, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, centre)
    assert display.highlit[3] == 0.3
    hover(QPoint(5, 5))
    assert display.highlit is None and darkest() == pytest.approx(plain)
