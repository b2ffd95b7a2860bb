"""VIEW_FACING controls as rviz 1.14 draws and drags them: the control's frame turns to the
camera (x: the view's direction, z: the camera's up), its markers with it unless
independent_marker_orientation keeps them the marker's; a MOVE_PLANE drag then moves in the
plane facing the camera."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from kame.rviz.camera import Camera
from kame.rviz.interact import Interaction, mouse_ray
from kame.rviz.interactive import InteractiveMarkers
from kame.rviz.scene import Scene
from tests.rviz.test_interact import Identity, _control, _display_with
from visualization_msgs.msg import InteractiveMarkerControl, Marker

WIDTH, HEIGHT = 800, 600


def _plate_control(mode: int, independent: bool) -> Any:
    """A control whose marker is a thin plate across its x axis."""
    control = _control("plate", mode, 1, 0, 0, 0)
    control.orientation_mode = InteractiveMarkerControl.VIEW_FACING
    control.independent_marker_orientation = independent
    plate = Marker(type=Marker.CUBE)
    plate.pose.orientation.w = 1.0
    plate.scale.x, plate.scale.y, plate.scale.z = 0.01, 1.0, 1.0
    plate.color.a = 1.0
    control.markers = [plate]
    return control


def _facing(display: InteractiveMarkers, camera: Camera) -> Scene:
    display.face(camera.view_matrix())
    scene = Scene()
    display.build(scene, Identity(), 0.0)
    return scene


def _forward(camera: Camera) -> np.ndarray:
    forward: np.ndarray = -camera.view_matrix()[2, :3]
    return forward


def test_a_view_facing_controls_frame_and_markers_face_the_camera_as_it_turns() -> None:
    display = _display_with(_plate_control(InteractiveMarkerControl.MOVE_PLANE, independent=False))
    camera = Camera()
    for _ in range(2):
        _facing(display, camera)
        handle = display.handles[0]
        frame, forward = handle.control_frame(), _forward(camera)
        assert frame[:3, 0] == pytest.approx(forward) and frame[:3, 2] == pytest.approx(camera.view_matrix()[1, :3])
        across = handle.triangles.reshape(-1, 3) @ forward
        assert np.abs(across).max() == pytest.approx(0.005, abs=1e-6)  # the plate faces the camera
        camera.rotate(120, -40)  # the camera turns: the next draw faces it again
        assert not np.allclose(_forward(camera), forward)


def test_independent_marker_orientation_keeps_the_markers_on_the_marker_but_not_the_drag_plane() -> None:
    display = _display_with(_plate_control(InteractiveMarkerControl.MOVE_PLANE, independent=True))
    camera = Camera()
    _facing(display, camera)
    handle = display.handles[0]
    assert np.abs(handle.triangles.reshape(-1, 3)[:, 0]).max() == pytest.approx(0.005, abs=1e-6)  # the marker's x
    centre = camera.project([[0.0, 0.0, 0.0]], WIDTH, HEIGHT)[0]
    interaction = Interaction("/rviz")
    assert interaction.press(display.handles, *mouse_ray(camera, centre[0], centre[1], WIDTH, HEIGHT)).consumed
    interaction.move(*mouse_ray(camera, centre[0] + 80, centre[1] + 50, WIDTH, HEIGHT))
    moved = handle.pose[:3, 3]
    assert float(np.linalg.norm(moved)) > 0.3
    assert float(moved @ _forward(camera)) == pytest.approx(0.0, abs=1e-9)  # in the plane facing the camera


def test_a_view_facing_ring_turns_about_the_views_direction() -> None:
    display = _display_with(_control("rotate", InteractiveMarkerControl.ROTATE_AXIS, 1, 0, 0, 0))
    display.handles[0].control.orientation_mode = InteractiveMarkerControl.VIEW_FACING
    camera = Camera()
    _facing(display, camera)
    forward = _forward(camera)
    ring = display.handles[0].triangles.reshape(-1, 3)
    assert np.abs(ring @ forward).max() == pytest.approx(0.0, abs=1e-6)  # rviz's default ring, facing the camera
    at = camera.project([ring[:3].mean(axis=0)], WIDTH, HEIGHT)[0]  # inside its first triangle
    interaction = Interaction("/rviz")
    assert interaction.press(display.handles, *mouse_ray(camera, at[0], at[1], WIDTH, HEIGHT)).consumed
    interaction.move(*mouse_ray(camera, WIDTH - at[0], HEIGHT - at[1], WIDTH, HEIGHT))  # half way round
    turned = display.handles[0].pose[:3, :3]
    axis = np.array([turned[2, 1] - turned[1, 2], turned[0, 2] - turned[2, 0], turned[1, 0] - turned[0, 1]])
    assert float(np.trace(turned)) < 0  # more than a quarter turn
    assert abs(float(axis @ forward)) == pytest.approx(float(np.linalg.norm(axis)), rel=1e-6)  # about the view


def test_a_menu_control_without_markers_is_rvizs_view_facing_button_and_opens_the_menu() -> None:
    """interactive_markers' autoComplete gives such a control its description as white text
    1.2 scales above the marker (basic_controls' "Options"); a click on it opens the menu."""
    from visualization_msgs.msg import InteractiveMarkerFeedback, MenuEntry

    control = _control("menu_only_control", InteractiveMarkerControl.MENU, 1, 0, 0, 0)
    control.description = "Options"
    display = _display_with(control)
    display.handles[0].marker.menu_entries = [MenuEntry(id=1, parent_id=0, title="First Entry")]
    camera = Camera()
    for turn in (0, 150):
        camera.rotate(turn, 0)
        label = _facing(display, camera).labels[0]
        assert label.text == "Options"
        assert label.position == pytest.approx([-0.025, 0.0, 1.2 - 0.025])
        interaction = Interaction("/rviz")
        on_text = camera.project([label.position], WIDTH, HEIGHT)[0] + [12, 0]  # in its second letter or so
        pressed = interaction.press(display.handles, *mouse_ray(camera, on_text[0], on_text[1], WIDTH, HEIGHT))
        assert [f.event_type for f in pressed.feedback][-1] == InteractiveMarkerFeedback.MOUSE_DOWN
        interaction.release()
        assert interaction.menu is display.handles[0]
        beside = camera.project([label.position], WIDTH, HEIGHT)[0] + [0, 40]
        assert not interaction.press(display.handles, *mouse_ray(camera, beside[0], beside[1], WIDTH, HEIGHT)).consumed
    control.description = ""  # nothing to show: as in rviz, nothing to click
    assert not _display_with(control).handles[0].triangles.size
