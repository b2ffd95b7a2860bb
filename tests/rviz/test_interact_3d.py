"""The Interact tool's 3-D modes without a window, as rviz 1.14 drags them by the camera's
axes: MOVE_3D in the plane facing the camera (Shift: along the ray it was grabbed by),
ROTATE_3D about the camera's up and right axes (Shift: about the view's direction),
MOVE_ROTATE_3D moving, and rotating with Ctrl."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from kame.rviz.camera import Camera
from kame.rviz.interact import Interaction, mouse_ray, pointer
from tests.rviz.test_interact import _control, _display_with
from visualization_msgs.msg import InteractiveMarkerControl, Marker

WIDTH, HEIGHT = 800, 600
QUARTER_TURN = 75 * 2 * 3.14 / 300  # rviz's 300 pixels a turn, 75 pixels


def _box_control(mode: int) -> Any:
    control = _control("box", mode, 1, 0, 0, 0)
    box = Marker(type=Marker.CUBE)
    box.pose.orientation.w = 1.0
    box.scale.x = box.scale.y = box.scale.z = 0.5
    box.color.a = 1.0
    control.markers = [box]
    return control


def _grabbed(mode: int, shift: bool = False, ctrl: bool = False) -> tuple[Interaction, Camera, Any, np.ndarray]:
    """The box's control pressed at its centre's pixel by an orbit camera."""
    display = _display_with(_box_control(mode))
    camera = Camera()
    centre = camera.project([[0.0, 0.0, 0.0]], WIDTH, HEIGHT)[0]
    interaction = Interaction("/rviz")
    pressed = interaction.press(display.handles, *mouse_ray(camera, centre[0], centre[1], WIDTH, HEIGHT),
                                at=pointer(camera, centre[0], centre[1], WIDTH, HEIGHT, shift, ctrl))
    assert pressed.consumed
    return interaction, camera, display.handles[0], centre


def _move(interaction: Interaction, camera: Camera, x: float, y: float, shift: bool = False,
          ctrl: bool = False) -> list[Any]:
    at = pointer(camera, x, y, WIDTH, HEIGHT, shift, ctrl)
    return interaction.move(*mouse_ray(camera, x, y, WIDTH, HEIGHT), at=at)


def _axes(camera: Camera) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    view = camera.view_matrix()
    return view[0, :3], view[1, :3], -view[2, :3]


def test_move_3d_keeps_the_grabbed_point_under_the_mouse_in_the_plane_facing_the_camera() -> None:
    interaction, camera, handle, centre = _grabbed(InteractiveMarkerControl.MOVE_3D)
    grab = interaction.drag.grab.copy() if interaction.drag else np.zeros(3)
    sent = _move(interaction, camera, centre[0] + 60, centre[1] - 40)
    assert len(sent) == 1
    moved = handle.pose[:3, 3]
    _, _, forward = _axes(camera)
    assert float(moved @ forward) == pytest.approx(0.0, abs=1e-9)  # in the plane facing the camera
    under = camera.project([grab + moved], WIDTH, HEIGHT)[0]
    assert under == pytest.approx([centre[0] + 60, centre[1] - 40], abs=1e-6)
    assert float(np.linalg.norm(moved)) > 0.3


def test_move_3d_with_shift_moves_along_the_ray_it_was_grabbed_by() -> None:
    interaction, camera, handle, centre = _grabbed(InteractiveMarkerControl.MOVE_3D, shift=True)
    ray = interaction.drag.ray.copy() if interaction.drag else np.zeros(3)
    eye = camera.eye()
    before = float(np.linalg.norm(handle.pose[:3, 3] - eye))
    _move(interaction, camera, centre[0], centre[1] + 20, shift=True)  # down: nearer the camera
    moved = handle.pose[:3, 3]
    assert float(np.linalg.norm(np.cross(moved, ray))) == pytest.approx(0.0, abs=1e-9)  # along the ray
    assert float(np.linalg.norm(moved - eye)) < before
    # rviz's metres a pixel: the control's y-z plane's (the box's x axis: its normal) at the grabbed point
    assert float(np.linalg.norm(moved)) == pytest.approx(20 * interaction.drag.metres_per_pixel)  # type: ignore[union-attr]
    _move(interaction, camera, centre[0] + 30, centre[1] + 20, shift=True)  # right is further: the larger wins
    assert float(np.linalg.norm(handle.pose[:3, 3] - eye)) > float(np.linalg.norm(moved - eye))


def test_rotate_3d_turns_about_the_cameras_up_and_right_axes_and_with_shift_about_the_view() -> None:
    interaction, camera, handle, centre = _grabbed(InteractiveMarkerControl.ROTATE_3D)
    right, up, forward = _axes(camera)
    _move(interaction, camera, centre[0] + 75, centre[1])
    pose = handle.pose
    assert pose[:3, 3] == pytest.approx([0, 0, 0], abs=1e-9)  # turned about its own origin
    expected = _rotation(up, QUARTER_TURN)
    assert pose[:3, :3] == pytest.approx(expected, abs=1e-9)
    _move(interaction, camera, centre[0] + 75, centre[1] + 75)  # then down: about the right axis
    assert handle.pose[:3, :3] == pytest.approx(_rotation(right, QUARTER_TURN) @ expected, abs=1e-9)
    interaction.release()
    interaction, camera, handle, centre = _grabbed(InteractiveMarkerControl.ROTATE_3D, shift=True)
    _move(interaction, camera, centre[0] + 10, centre[1] + 75, shift=True)  # the larger of x and y
    assert handle.pose[:3, :3] == pytest.approx(_rotation(forward, QUARTER_TURN), abs=1e-9)


def test_move_rotate_3d_moves_and_rotates_with_ctrl() -> None:
    interaction, camera, handle, centre = _grabbed(InteractiveMarkerControl.MOVE_ROTATE_3D)
    _move(interaction, camera, centre[0] + 50, centre[1])
    moved = handle.pose.copy()
    assert float(np.linalg.norm(moved[:3, 3])) > 0.3 and moved[:3, :3] == pytest.approx(np.eye(3))
    _move(interaction, camera, centre[0] + 125, centre[1], ctrl=True)  # Ctrl pressed: the motion restarts
    assert handle.pose == pytest.approx(moved)
    _move(interaction, camera, centre[0] + 200, centre[1], ctrl=True)
    _, up, _ = _axes(camera)
    assert handle.pose[:3, 3] == pytest.approx(moved[:3, 3]) and handle.pose[:3, :3] == pytest.approx(
        _rotation(up, QUARTER_TURN), abs=1e-9)


def _rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rotation by `angle` about unit `axis`, by Euler-Rodrigues from the quaternion."""
    w, (x, y, z) = math.cos(angle / 2), axis * math.sin(angle / 2)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def test_the_wheel_during_a_move_3d_drag_moves_along_the_grabbing_ray() -> None:
    """rviz's moveZAxisWheel: 2 m along the ray a notch (Qt's 120), forward away from the camera."""
    interaction, _, handle, _ = _grabbed(InteractiveMarkerControl.MOVE_ROTATE_3D)
    ray = interaction.drag.ray.copy() if interaction.drag else np.zeros(3)
    assert len(interaction.wheel(120)) == 1
    assert handle.pose[:3, 3] == pytest.approx(2 * ray)
    interaction.wheel(-60)
    assert handle.pose[:3, 3] == pytest.approx(1 * ray)
    interaction.release()
    interaction, _, handle, _ = _grabbed(InteractiveMarkerControl.ROTATE_3D)
    assert interaction.wheel(120) == [] and handle.pose == pytest.approx(np.eye(4))
