"""The InteractiveMarkers display and the Interact tool without a window: a server's markers
drawn with their controls, a drag along each interaction mode's geometry giving the pose
rviz would send, and the feedback's fields."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from kame.interactive_markers.server_state import ServerState
from kame.rviz.camera import TOP_DOWN, Camera
from kame.rviz.config import DISPLAY_CLASSES
from kame.rviz.interact import Interaction, dragged, mouse_ray, ray_triangles
from kame.rviz.interactive import InteractiveMarkers
from kame.rviz.scene import Scene
from visualization_msgs.msg import InteractiveMarker, InteractiveMarkerControl, InteractiveMarkerFeedback

SQRT_HALF = math.sqrt(0.5)


class Identity:
    fixed_frame = "fixed"

    def transform(self, frame_id: str) -> np.ndarray:
        return np.eye(4)

    def names(self) -> list[str]:
        return ["base_link"]

    def parent(self, frame_id: str) -> str | None:
        return None


def _control(name: str, mode: int, w: float, x: float, y: float, z: float) -> Any:
    control = InteractiveMarkerControl(name=name, interaction_mode=mode)
    control.orientation.w, control.orientation.x, control.orientation.y, control.orientation.z = w, x, y, z
    return control


def _display_with(*controls: Any) -> InteractiveMarkers:
    marker = InteractiveMarker(name="box", scale=1.0, description="Simple 1-DOF Control")
    marker.header.frame_id = "base_link"
    marker.pose.orientation.w = 1.0
    marker.controls = list(controls)
    server = ServerState("/basic_controls")
    server.insert(marker)
    display = InteractiveMarkers(options={"Update Topic": "/basic_controls/update"})
    display.receive([server.apply_changes()], 0.0)
    display.receive_side("/basic_controls/update_full", [server.init_message()], 0.0)
    scene = Scene()
    display.build(scene, Identity(), 0.0)
    assert display.status.level == "Ok", display.status.text
    return display


def test_the_display_is_rvizs_and_follows_the_update_namespace() -> None:
    cls = DISPLAY_CLASSES["rviz/InteractiveMarkers"]
    display = cls(options={"Update Topic": "/basic_controls/update"})
    assert display.subscription() == ("/basic_controls/update", "visualization_msgs/InteractiveMarkerUpdate")
    assert display.side_topics() == {"/basic_controls/update_full": "visualization_msgs/InteractiveMarkerInit"}
    newer = cls(options={"Interactive Markers Namespace": "/simple_marker"})  # rviz 1.13's key
    assert newer.topic == "/simple_marker/update"


def test_controls_without_markers_get_rvizs_arrows_and_rings_in_the_axis_colour() -> None:
    display = _display_with(_control("move_x", InteractiveMarkerControl.MOVE_AXIS, 1, 1, 0, 0),
                            _control("rotate_z", InteractiveMarkerControl.ROTATE_AXIS, SQRT_HALF, 0, -SQRT_HALF, 0))
    move, rotate = display.handles
    assert len(move.triangles) and len(rotate.triangles)
    assert move.triangles[:, :, 0].max() == pytest.approx(1.0, abs=1e-6)  # arrows along x to the scale
    assert np.ptp(rotate.triangles[:, :, 2]) < 1e-6  # the z ring lies in the x-y plane
    assert np.linalg.norm(rotate.triangles[:, :, :2], axis=2).max() == pytest.approx(0.6, abs=1e-3)


def test_a_ray_meets_the_nearest_triangle() -> None:
    triangles = np.array([[[0, -1, -1], [0, 1, -1], [0, 0, 1]], [[2, -1, -1], [2, 1, -1], [2, 0, 1]]], dtype=float)
    assert ray_triangles(np.array([-5.0, 0, 0]), np.array([1.0, 0, 0]), triangles) == pytest.approx(5.0)
    assert ray_triangles(np.array([-5.0, 5, 0]), np.array([1.0, 0, 0]), triangles) is None


def test_each_mode_drags_by_its_geometry() -> None:
    start, frame = np.eye(4), np.eye(4)  # control axis: x
    grab = np.array([0.8, 0.0, 0.0])
    down = np.array([0.0, 0.0, -1.0])
    moved = dragged(InteractiveMarkerControl.MOVE_AXIS, start, frame, grab, np.array([2.3, 0.7, 5.0]), down)
    assert moved[:3, 3] == pytest.approx([1.5, 0.0, 0.0])  # only along the axis
    z_axis = np.array([[0.0, 0, 1, 0], [0, 1, 0, 0], [-1, 0, 0, 0], [0, 0, 0, 1]])  # control x -> fixed z
    moved = dragged(InteractiveMarkerControl.MOVE_PLANE, start, z_axis, grab, np.array([1.8, 2.0, 5.0]), down)
    assert moved[:3, 3] == pytest.approx([1.0, 2.0, 0.0])
    turned = dragged(InteractiveMarkerControl.ROTATE_AXIS, start, z_axis, grab, np.array([0.0, 3.0, 5.0]), down)
    assert turned[:3, 3] == pytest.approx([0, 0, 0]) and turned[:3, 0] == pytest.approx([0, 1, 0])
    leash = dragged(InteractiveMarkerControl.MOVE_ROTATE, start, z_axis, grab, np.array([0.0, 3.0, 5.0]), down)
    assert leash[:3, 0] == pytest.approx([0, 1, 0]) and leash[:3, 3] == pytest.approx([0, 2.2, 0])
    assert dragged(InteractiveMarkerControl.MOVE_PLANE, start, np.eye(4), grab, np.zeros(3), down) is None


def test_a_drag_in_the_view_sends_rvizs_feedback_in_its_order() -> None:
    display = _display_with(_control("move_x", InteractiveMarkerControl.MOVE_AXIS, 1, 1, 0, 0))
    camera = Camera(scale=100.0)
    camera.become(TOP_DOWN)
    width = height = 400
    tip = camera.project([[0.9, 0.0, 0.0]], width, height)[0]  # on the +x arrow, seen from above
    interaction = Interaction("/rviz_123")
    pressed = interaction.press(display.handles, *mouse_ray(camera, tip[0], tip[1], width, height))
    assert pressed.consumed and [f.event_type for f in pressed.feedback] == [InteractiveMarkerFeedback.POSE_UPDATE,
                                                                             InteractiveMarkerFeedback.MOUSE_DOWN]
    down = pressed.feedback[1]
    assert (down.client_id, down.marker_name, down.control_name) == ("/rviz_123/InteractiveMarkers", "box", "move_x")
    assert down.mouse_point_valid and down.mouse_point.x == pytest.approx(0.9, abs=0.02)
    # 50 px to the right and 30 down: half a metre along x, nothing across it
    sent = interaction.move(*mouse_ray(camera, tip[0] + 50, tip[1] + 30, width, height))
    assert [f.event_type for f in sent] == [InteractiveMarkerFeedback.POSE_UPDATE]
    pose = sent[0].pose
    assert (pose.position.x, pose.position.y, pose.position.z) == pytest.approx((0.5, 0.0, 0.0), abs=1e-6)
    assert sent[0].header.frame_id == "base_link"
    marker = display.handles[0].marker
    marker.header.stamp.secs = 7  # stamped: not locked to its frame, answered in the fixed frame
    display.handles[0].reference = np.array([[1.0, 0, 0, 10], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    stamped = interaction.feedback(display.handles[0], InteractiveMarkerFeedback.POSE_UPDATE, None)
    assert (stamped.header.frame_id, stamped.header.stamp.secs, stamped.pose.position.x) == ("fixed", 7, 10.5)
    marker.header.stamp.secs = 0
    display.handles[0].reference = np.eye(4)
    assert display.handles[0].marker.pose.position.x == pytest.approx(0.5)  # moved in the view at once
    assert [f.event_type for f in interaction.release()] == [InteractiveMarkerFeedback.POSE_UPDATE,
                                                             InteractiveMarkerFeedback.MOUSE_UP]
    empty = interaction.press(display.handles, *mouse_ray(camera, 10, 10, width, height))
    assert not empty.consumed and interaction.drag is None


def test_a_button_click_and_a_menu() -> None:
    from visualization_msgs.msg import Marker, MenuEntry

    button = _control("click", InteractiveMarkerControl.BUTTON, 1, 0, 0, 0)
    box = Marker(type=Marker.CUBE)
    box.pose.orientation.w = 1.0
    box.scale.x = box.scale.y = box.scale.z = 0.45
    box.color.r = box.color.a = 1.0
    button.markers = [box]
    display = _display_with(button)
    interaction = Interaction("/rviz")
    origin, direction = np.array([0.0, 0.0, 5.0]), np.array([0.0, 0.0, -1.0])
    assert not interaction.press(display.handles, origin, direction, right=True).consumed  # no menu: the camera's
    display.handles[0].marker.menu_entries = [MenuEntry(id=1, parent_id=0, title="First Entry")]
    interaction.press(display.handles, origin, direction)
    assert [f.event_type for f in interaction.release()] == [InteractiveMarkerFeedback.BUTTON_CLICK,
                                                             InteractiveMarkerFeedback.POSE_UPDATE,
                                                             InteractiveMarkerFeedback.MOUSE_UP]
    assert interaction.menu is None  # a left click on a BUTTON opens no menu
    pressed = interaction.press(display.handles, origin, direction, right=True)
    assert pressed.consumed and interaction.drag is None and interaction.menu is None  # rviz: not yet
    assert interaction.release() == [] and interaction.menu is display.handles[0]  # on the release
    chosen = interaction.menu_select(interaction.menu, 1)
    assert (chosen.event_type, chosen.menu_entry_id) == (InteractiveMarkerFeedback.MENU_SELECT, 1)


def test_a_menu_control_opens_its_menu_on_the_left_release_after_rvizs_mouse_down() -> None:
    from visualization_msgs.msg import Marker, MenuEntry

    menu = _control("menu_only_control", InteractiveMarkerControl.MENU, 1, 0, 0, 0)
    box = Marker(type=Marker.CUBE)
    box.pose.orientation.w = 1.0
    box.scale.x = box.scale.y = box.scale.z = 0.45
    box.color.a = 1.0
    menu.markers = [box]
    display = _display_with(menu)
    display.handles[0].marker.menu_entries = [MenuEntry(id=1, parent_id=0, title="First Entry")]
    interaction = Interaction("/rviz")
    origin, direction = np.array([0.0, 0.0, 5.0]), np.array([0.0, 0.0, -1.0])
    pressed = interaction.press(display.handles, origin, direction)
    assert [f.event_type for f in pressed.feedback] == [InteractiveMarkerFeedback.POSE_UPDATE,
                                                        InteractiveMarkerFeedback.MOUSE_DOWN]
    assert interaction.menu is None and interaction.move(origin + 0.1, direction) == []  # it does not drag
    assert [f.event_type for f in interaction.release()] == [InteractiveMarkerFeedback.POSE_UPDATE,
                                                             InteractiveMarkerFeedback.MOUSE_UP]
    assert interaction.menu is display.handles[0]


def test_the_display_loads_and_saves_in_a_rviz_file(tmp_path: Any) -> None:
    from kame.rviz import config

    path = tmp_path / "im.rviz"
    path.write_text("""\
Visualization Manager:
  Displays:
    - Class: rviz/InteractiveMarkers
      Enable Transparency: true
      Enabled: true
      Name: InteractiveMarkers
      Show Axes: false
      Show Descriptions: true
      Show Visual Aids: false
      Update Topic: /basic_controls/update
      Value: true
  Global Options:
    Fixed Frame: base_link
""")
    loaded = config.load(str(path))
    display = loaded.displays[0]
    assert isinstance(display, InteractiveMarkers) and display.topic == "/basic_controls/update"
    config.save(loaded, str(tmp_path / "again.rviz"))
    again = config.load(str(tmp_path / "again.rviz")).displays[0]
    assert again.class_name == "rviz/InteractiveMarkers" and again.options["Update Topic"] == "/basic_controls/update"
    assert "Update Topic: /basic_controls/update" in (tmp_path / "again.rviz").read_text()


def test_a_highlit_control_is_drawn_brighter_and_the_others_not() -> None:
    """rviz adds 0.3 to the colour of the control under the mouse (0.5 pressed), clamped at 1."""
    display = _display_with(_control("move_x", InteractiveMarkerControl.MOVE_AXIS, 1, 1, 0, 0),
                            _control("move_y", InteractiveMarkerControl.MOVE_AXIS, SQRT_HALF, 0, 0, SQRT_HALF))

    def colours() -> list[list[float]]:
        scene = Scene()
        display.build(scene, Identity(), 0.0)
        drawn = np.concatenate([b.float_colors() for b in scene.batches]).astype(float)
        return sorted(np.unique(drawn.round(3), axis=0).tolist())

    assert colours() == [[0.0, 1.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0]]  # y: green arrows, x: red
    display.highlight(display.handles[1], 0.3)
    assert colours() == [[0.3, 1.0, 0.3, 1.0], [1.0, 0.0, 0.0, 1.0]]  # move_y brighter, move_x as it was
    display.highlight(display.handles[0], 0.5)
    assert colours() == [[0.0, 1.0, 0.0, 1.0], [1.0, 0.5, 0.5, 1.0]]
    display.highlight(None, 0.3)
    assert colours() == [[0.0, 1.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0]]
