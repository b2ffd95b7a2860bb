"""rviz's model without a window: the camera projects where rviz's would, each display puts its
geometry at the right place in the fixed frame (or says why it cannot), markers come and go as
rviz's do, and .rviz files load and save."""

from __future__ import annotations

import io
import math
import random
from typing import Any

import numpy as np
import pytest

from geometry_msgs.msg import Point, PointStamped, Pose, PoseArray, PoseStamped, Quaternion
from kame.rviz import backlog, config, displays, markers
from kame.rviz.camera import FPS, TOP_DOWN, Camera
from kame.rviz.display import OK, WARN, edited_option
from kame.rviz.scene import Scene, apply, box_triangles, cylinder_triangles, pose_matrix, sphere_triangles
from nav_msgs.msg import OccupancyGrid, Odometry, Path
from sensor_msgs.msg import LaserScan, PointCloud2, PointField
from std_msgs.msg import ColorRGBA
from visualization_msgs.msg import Marker, MarkerArray


class TreeOf:
    """A tf tree of fixed offsets: frame -> (parent, translation)."""

    def __init__(self, fixed_frame: str, offsets: dict[str, tuple[str, tuple[float, float, float]]]) -> None:
        self.fixed_frame = fixed_frame
        self.offsets = offsets

    def transform(self, frame_id: str) -> np.ndarray | str:
        matrix = np.eye(4)
        frame = frame_id
        while frame != self.fixed_frame:
            if frame not in self.offsets:
                return f"no transform from {frame_id} to {self.fixed_frame}"
            parent, translation = self.offsets[frame]
            step = np.eye(4)
            step[:3, 3] = translation
            matrix = step @ matrix
            frame = parent
        return matrix

    def names(self) -> list[str]:
        return [self.fixed_frame, *self.offsets]

    def parent(self, frame_id: str) -> str | None:
        return self.offsets.get(frame_id, (None, None))[0]


TREE = TreeOf("map", {"odom": ("map", (1.0, 0.0, 0.0)), "laser": ("odom", (0.0, 2.0, 0.0))})


def build(display, *messages, now=0.0):  # type: ignore[no-untyped-def]
    scene = Scene()
    display.receive(list(messages), now)
    display.build(scene, TREE, now)
    return scene


def unwound(vertices: np.ndarray) -> np.ndarray:
    """Triangles with each one's corners in one order, whichever way it was wound."""
    triangles = np.asarray(vertices, dtype=float).reshape(-1, 3, 3)
    order = np.array([np.lexsort((t[:, 2].round(4), t[:, 1].round(4), t[:, 0].round(4))) for t in triangles])
    return np.take_along_axis(triangles, order[:, :, None], axis=1)


def without_flat(vertices: np.ndarray) -> np.ndarray:
    """The triangles that have an area."""
    triangles = np.asarray(vertices, dtype=float).reshape(-1, 3, 3)
    areas = np.linalg.norm(np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]), axis=1)
    kept: np.ndarray = triangles[areas > 1e-9].reshape(-1, 3)
    return kept


def all_vertices(scene: Scene) -> np.ndarray:
    return np.vstack([b.vertices for b in scene.batches])


def test_orbit_camera_projects_the_focal_point_to_the_centre_and_turns_with_the_mouse() -> None:
    camera = Camera(focal_point=np.array([1.0, 2.0, 0.0]))
    assert camera.project([[1.0, 2.0, 0.0]], 640, 480)[0] == pytest.approx([320, 240])
    before = camera.project([[2.0, 2.0, 0.0]], 640, 480)[0]
    camera.rotate(100, 0)
    assert not np.allclose(camera.project([[2.0, 2.0, 0.0]], 640, 480)[0], before)
    distance = camera.distance
    camera.zoom(1)
    assert camera.distance == pytest.approx(distance * 0.9)
    camera.pan(50, 0, 480)
    assert camera.project([[1.0, 2.0, 0.0]], 640, 480)[0][0] == pytest.approx(370, abs=1)


def test_top_down_view_has_x_right_and_y_up() -> None:
    camera = Camera(kind=TOP_DOWN, scale=100.0)
    centre, east, north = camera.project([[0, 0, 0], [1, 0, 0], [0, 1, 0]], 400, 400)
    assert centre == pytest.approx([200, 200])
    assert east == pytest.approx([300, 200])
    assert north == pytest.approx([200, 100])


def test_laser_scan_points_are_placed_through_tf_and_a_missing_frame_is_the_status() -> None:
    scan = LaserScan(angle_min=0.0, angle_increment=math.pi / 2, range_min=0.1, range_max=10.0,
                     ranges=[1.0, 2.0, float("inf")])
    scan.header.frame_id = "laser"
    display = displays.LaserScan()
    scene = build(display, scan)
    assert display.status.level == OK
    assert all_vertices(scene) == pytest.approx(np.array([[2.0, 2.0, 0.0], [1.0, 4.0, 0.0]]))
    scan.header.frame_id = "base_laser"
    build(display, scan)
    assert display.status.level == WARN and "no transform from base_laser to map" in display.status.text


def test_a_display_without_messages_says_so() -> None:
    display = displays.Path(options={"Topic": "/plan"})
    build(display)
    assert display.status.level == WARN and "/plan" in display.status.text


def test_pointcloud2_xyz_rgb() -> None:
    points = np.zeros(3, dtype=[("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("rgb", "<u4")])
    points["x"], points["z"] = [1, np.nan, 2], [0.5, 0.5, 0.5]  # the NaN point is not drawn
    points["rgb"] = [0xFF0000, 0x0000FF, 0x00FF00]
    fields = [PointField(name=n, offset=o, datatype=d, count=1) for n, o, d in
              (("x", 0, 7), ("y", 4, 7), ("z", 8, 7), ("rgb", 12, 7))]
    cloud = PointCloud2(height=1, width=3, fields=fields, is_bigendian=False, point_step=16, row_step=48,
                        data=points.tobytes(), is_dense=False)
    cloud.header.frame_id = "odom"
    scene = build(displays.PointCloud2(options={"Alpha": 0.5}), cloud)
    batch = scene.batches[0]
    assert batch.vertices.dtype == np.float32
    assert batch.vertices == pytest.approx(np.array([[2, 0, 0.5], [3, 0, 0.5]]))
    assert batch.colors.dtype == np.uint8  # 4 bytes a point to upload
    assert batch.colors.tolist() == [[255, 0, 0, 128], [0, 255, 0, 128]]
    unchosen = build(displays.PointCloud2(options={"Color Transformer": ""}), cloud).batches[0]  # as rviz saves it
    assert unchosen.colors.tolist() == [[255, 0, 0, 255], [0, 255, 0, 255]]
    plain = build(displays.PointCloud2(options={"Color Transformer": "FlatColor", "Color": "0; 0; 255"}),
                  cloud).batches[0]
    assert plain.uniform and plain.colors[1] == pytest.approx([0, 0, 1, 1])  # one colour: no colour array


def test_occupancy_grid_is_a_texture_on_its_origin_with_rvizs_map_colours() -> None:
    grid = OccupancyGrid(data=[0, 100, -1, 50])
    grid.header.frame_id = "map"
    grid.info.width, grid.info.height, grid.info.resolution = 2, 2, 0.5
    grid.info.origin.position.x = -1.0
    grid.info.origin.orientation.w = 1.0
    scene = build(displays.OccupancyGrid(options={"Alpha": 1.0}), grid)
    texture = scene.textures[0]
    assert texture.corners[0] == pytest.approx([-1, 0, 0]) and texture.corners[2] == pytest.approx([0, 1, 0])
    assert texture.rgba[0, 0, :3].tolist() == [255, 255, 255] and texture.rgba[0, 1, :3].tolist() == [0, 0, 0]
    assert texture.rgba[1, 0, :3].tolist() == [0x70, 0x89, 0x86]
    costmap = build(displays.OccupancyGrid(options={"Color Scheme": "costmap"}), grid).textures[0]
    assert costmap.rgba[0, 1, :3].tolist() == [255, 0, 255]


def test_pose_path_odometry_posearray_point() -> None:
    pose = PoseStamped(pose=Pose(position=Point(1, 1, 0), orientation=Quaternion(0, 0, 0, 1)))
    pose.header.frame_id = "map"
    vertices = all_vertices(build(displays.Pose(), pose))
    assert vertices[:, 0].max() == pytest.approx(2.3, abs=0.01) and vertices[:, 1].mean() == pytest.approx(1, abs=0.01)
    path = Path(poses=[PoseStamped(pose=Pose(position=Point(x, 0, 0))) for x in (0, 1, 2)])
    path.header.frame_id = "odom"
    assert all_vertices(build(displays.Path(), path))[:, 0].tolist() == [1, 2, 2, 3]
    odometry = displays.Odometry()
    moves = [Odometry() for _ in range(3)]
    for x, message in zip((0.0, 0.01, 1.0), moves, strict=True):
        message.header.frame_id = "map"
        message.pose.pose.position.x = x
        message.pose.pose.orientation.w = 1.0
    build(odometry, *moves)
    assert len(odometry.kept) == 2  # the 1 cm move is within the position tolerance
    array = PoseArray(poses=[Pose(orientation=Quaternion(0, 0, 0, 1))] * 3)
    array.header.frame_id = "laser"
    assert len(all_vertices(build(displays.PoseArray(), array))) == 18
    point = PointStamped(point=Point(0, 0, 1))
    point.header.frame_id = "laser"
    assert all_vertices(build(displays.PointStamped(), point)).mean(axis=0) == pytest.approx([1, 2, 1], abs=0.05)


def _marker(ns: str, marker_id: int, kind: int, action: int = 0, lifetime: float = 0.0) -> Marker:
    marker = Marker(ns=ns, id=marker_id, type=kind, action=action)
    marker.header.frame_id = "odom"
    marker.pose.orientation.w = 1.0
    marker.scale.x = marker.scale.y = marker.scale.z = 1.0
    marker.color.r = marker.color.a = 1.0
    marker.lifetime.secs = int(lifetime)
    marker.points = [Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0)]
    marker.text = "hello"
    return marker


def test_every_marker_type_draws_and_markers_are_replaced_deleted_and_expire() -> None:
    display = markers.MarkerArray()
    array = MarkerArray(markers=[_marker("shapes", kind, kind) for kind in range(12) if kind != markers.MESH])
    scene = build(display, array)
    assert display.status.level == OK
    assert [label.text for label in scene.labels] == ["hello"]
    kinds = {b.kind for b in scene.batches}
    assert kinds == {"triangles", "lines", "points"}
    # one batch a kind (closed solids' triangles apart from the rest): 2,000 markers, a few draw calls
    assert len(scene.batches) == 4 and sum(b.closed for b in scene.batches) == 1
    cube = build(markers.Marker(), _marker("one", 1, markers.CUBE)).batches[0].vertices
    assert cube.min(axis=0) == pytest.approx([0.5, -0.5, -0.5]) and cube.max(axis=0) == pytest.approx([1.5, 0.5, 0.5])
    build(display, MarkerArray(markers=[_marker("shapes", 1, 1, action=markers.DELETE)]))
    assert ("shapes", 1) not in display.markers and len(display.markers) == 10
    build(display, MarkerArray(markers=[_marker("", 0, 0, action=markers.DELETEALL)]))
    assert display.markers == {}
    single = markers.Marker()
    first = build(single, _marker("brief", 0, markers.SPHERE, lifetime=1.0), now=10.0).batches[0]
    assert build(single, now=10.5).batches[0] is first  # alive a while yet: the same scene, not redrawn
    assert not build(single, now=11.5).batches and single.markers == {}



def _serialized(message: Any) -> bytes:
    out = io.BytesIO()
    message.serialize(out)
    return out.getvalue()


def _random_marker(rng: random.Random) -> Marker:
    """A marker whose every variable-length part (frame, ns, points, colours, text, mesh) varies,
    so reading its keys off the bytes must step over each; its x says which message it came in."""
    marker = Marker(ns=rng.choice(["a", "b", "ü"]), id=rng.randrange(4), type=rng.randrange(12),
                    action=rng.choice([markers.ADD, markers.ADD, 1, markers.DELETE, markers.DELETEALL]),
                    text="t" * rng.randrange(3), mesh_resource="m" * rng.randrange(3))
    marker.header.frame_id = rng.choice(["", "map", "base_link"])
    marker.points = [Point(rng.random(), 0.0, 0.0) for _ in range(rng.randrange(3))]
    marker.colors = [ColorRGBA(rng.random(), 0.0, 0.0, 1.0) for _ in range(rng.randrange(3))]
    marker.pose.position.x = rng.random()
    return marker


@pytest.mark.parametrize("array", [True, False])
def test_the_marker_messages_a_backlog_needs_leave_the_markers_every_message_would(array: bool) -> None:
    rng = random.Random(18)
    dropped = 0
    for _ in range(400):
        if array:
            messages: list[Any] = [MarkerArray(markers=[_random_marker(rng) for _ in range(rng.randrange(4))])
                                   for _ in range(rng.randrange(1, 7))]
        else:
            messages = [_random_marker(rng) for _ in range(rng.randrange(1, 7))]
        payloads = [_serialized(message) for message in messages]
        for message, payload in zip(messages, payloads, strict=True):
            shown = message.markers if array else [message]
            assert backlog.marker_keys(payload, array) == [(m.ns.encode(), m.id, m.action) for m in shown]
        kept = backlog.still_needed(payloads, array)
        assert kept[-1] is payloads[-1]  # the newest is the display's message
        dropped += len(payloads) - len(kept)
        every, reduced = (markers.MarkerArray() if array else markers.Marker() for _ in range(2))
        before = [_random_marker(rng) for _ in range(6)]  # what the display had: a DELETEALL must clear it
        for display in (every, reduced):
            display.receive([MarkerArray(markers=before)] if array else before, 0.0)
        every.receive(messages, 1.0)
        cls = MarkerArray if array else Marker
        reduced.receive([cls().deserialize(payload) for payload in kept], 1.0)
        assert {key: _serialized(m) for key, (m, _) in reduced.markers.items()} == \
            {key: _serialized(m) for key, (m, _) in every.markers.items()}
    assert dropped > 200  # the backlogs were thinned, not all kept


def test_a_backlog_of_repeated_arrays_is_one_array_and_a_delete_or_deleteall_is_never_skipped() -> None:
    def array(*markers_: Marker) -> bytes:
        return _serialized(MarkerArray(markers=list(markers_)))

    same = [array(*(_marker("flood", i, markers.CUBE) for i in range(10))) for _ in range(5)]
    assert backlog.still_needed(same, True) == same[-1:]
    delete = array(_marker("flood", 3, markers.CUBE, action=markers.DELETE))
    clear = array(_marker("", 0, 0, action=markers.DELETEALL))
    later = array(*(_marker("flood", i, markers.CUBE) for i in range(10) if i != 3))
    assert backlog.still_needed([*same, delete, *same], True) == same[-1:]  # 3 is added again after
    assert backlog.still_needed([*same, delete, later], True) == [delete, later]
    assert backlog.still_needed([*same, clear, later], True) == [clear, later]
    assert backlog.still_needed([*same, clear, later, clear, later], True) == [clear, later]
    assert backlog.still_needed([same[0], b"\x05\x00\x00\x00", same[0]], True) == [b"\x05\x00\x00\x00", same[0]]

def test_hidden_namespace_and_unknown_frame() -> None:
    display = markers.Marker(options={"Namespaces": {"hidden": False}})
    hidden = _marker("hidden", 0, markers.CUBE)
    lost = _marker("lost", 0, markers.CUBE)
    lost.header.frame_id = "nowhere"
    scene = build(display, hidden, lost)
    assert not scene.batches
    assert display.status.level == WARN and "lost/0" in display.status.text and "nowhere" in display.status.text


def test_tf_display_draws_every_frame_with_its_name_and_parent_arrows() -> None:
    display = displays.TF()
    scene = build(display)
    assert sorted(label.text for label in scene.labels) == ["laser", "map", "odom"]
    laser = next(label for label in scene.labels if label.text == "laser")
    assert laser.position == pytest.approx([1, 2, 0])
    arrows = scene.batches[-1].vertices
    assert len(arrows) == 4  # odom -> map and laser -> odom


RVIZ_FILE = """\
Panels:
  - Class: rviz/Displays
    Name: Displays
Visualization Manager:
  Class: ""
  Displays:
    - Alpha: 0.5
      Cell Size: 1
      Class: rviz/Grid
      Color: 160; 160; 164
      Enabled: true
      Name: Grid
      Plane Cell Count: 10
      Reference Frame: <Fixed Frame>
      Value: true
    - Class: rviz/LaserScan
      Color: 0; 255; 0
      Enabled: true
      Name: LaserScan
      Topic: /scan
      Size (m): 0.05
    - Class: rviz/DepthCloud
      Enabled: true
      Name: DepthCloud
  Enabled: true
  Global Options:
    Background Color: 48; 48; 48
    Fixed Frame: odom
    Frame Rate: 30
  Views:
    Current:
      Class: rviz/Orbit
      Distance: 12.5
      Focal Point:
        X: 1
        Y: 2
        Z: 0
      Pitch: 0.6
      Yaw: 0.3
    Saved: ~
"""


def test_an_rviz_file_loads_and_saves_back_what_it_had() -> None:
    loaded = config.parse(RVIZ_FILE)
    assert loaded.fixed_frame == "odom" and loaded.frame_rate == 30
    assert [d.class_name for d in loaded.displays] == ["rviz/Grid", "rviz/LaserScan"]
    assert loaded.displays[1].color()[:3] == (0, 1, 0) and loaded.displays[1].topic == "/scan"
    assert loaded.camera.distance == 12.5 and loaded.camera.focal_point.tolist() == [1, 2, 0]
    again = config.parse(config.dump(loaded))
    assert [d.name for d in again.displays] == ["Grid", "LaserScan"]
    assert again.displays[1].options["Size (m)"] == 0.05
    assert [e["Class"] for e in again.unknown_displays] == ["rviz/DepthCloud"]
    assert again.camera.pitch == 0.6 and again.fixed_frame == "odom"
    with pytest.raises(ValueError):
        config.parse("- just a list")


def test_an_rviz_file_with_sections_of_the_wrong_shape_opens_with_the_defaults() -> None:
    # tests/fuzz found these: AttributeError, or "cannot convert float NaN to integer"
    for text in ("Visualization Manager: 1", "Visualization Manager: {Views: [1], Displays: 3}",
                 "Visualization Manager: {Global Options: {Frame Rate: .nan}, Views: {Current: {Focal Point: 2}}}"):
        loaded = config.parse(text)
        assert loaded.frame_rate == 30 and loaded.displays == [] and loaded.camera.focal_point.tolist() == [0, 0, 0]
        assert config.parse(config.dump(loaded)).fixed_frame == "map"


def test_first_person_view_looks_from_its_eye_and_moves_as_rvizs() -> None:
    camera = Camera(kind=FPS, position=np.array([0.0, 0.0, 1.0]), yaw=0.0, pitch=0.0)
    ahead, left, behind = camera.project([[5.0, 0.0, 1.0], [5.0, 1.0, 1.0], [-5.0, 0.0, 1.0]], 640, 480)
    assert ahead == pytest.approx([320, 240]) and left[0] < 320 and np.isnan(behind).all()
    camera.rotate(0, 100)  # dragging down looks down
    assert camera.project([[5.0, 0.0, 1.0]], 640, 480)[0][1] < 240
    camera.pitch = 0.0
    camera.zoom(1)  # a wheel notch: 1.2 m forward
    assert camera.eye() == pytest.approx([1.2, 0.0, 1.0])
    camera.pan(100, 0, 480)  # 1 cm a pixel, to the right (the view's -y)
    assert camera.eye() == pytest.approx([1.2, -1.0, 1.0])


def test_switching_views_keeps_what_is_seen() -> None:
    camera = Camera(focal_point=np.array([1.0, 2.0, 0.0]))
    seen = camera.project([[1.0, 2.0, 0.0], [2.0, 2.0, 0.5]], 640, 480)
    camera.become(FPS)
    assert camera.kind == FPS and camera.project([[1.0, 2.0, 0.0], [2.0, 2.0, 0.5]], 640, 480) == pytest.approx(seen)
    camera.position = camera.position + np.array([0.5, 0.0, 0.0])
    camera.become("rviz/Orbit")
    assert camera.project([[1.5, 2.0, 0.0]], 640, 480)[0] == pytest.approx([320, 240])


def test_a_first_person_view_loads_and_saves() -> None:
    text = """Visualization Manager:
  Views:
    Current:
      Class: rviz/FPS
      Name: Current View
      Pitch: 0.4
      Position: {X: -5, Y: 1, Z: 3}
      Yaw: 0.2
"""
    camera = config.parse(text).camera
    assert camera.kind == FPS and camera.position == pytest.approx([-5, 1, 3])
    assert (camera.pitch, camera.yaw) == pytest.approx((0.4, 0.2))
    assert config.view_entry(camera)["Position"] == {"X": -5.0, "Y": 1.0, "Z": 3.0}


@pytest.mark.parametrize("kind", ["rviz/Orbit", TOP_DOWN, FPS])
def test_a_click_finds_the_ground_point_the_camera_projects_there(kind: str) -> None:
    camera = Camera(kind=kind, focal_point=np.array([2.0, -1.0, 0.0]), scale=50.0)
    ground = np.array([[3.0, 0.5, 0.0]])
    pixel = camera.project(ground, 800, 600)[0]
    hit = camera.ground_point(pixel[0], pixel[1], 800, 600)
    assert hit is not None and hit == pytest.approx(ground[0], abs=1e-6)


def test_a_display_reuses_its_scene_until_its_message_options_or_transforms_change() -> None:
    scan = LaserScan(angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=10.0, ranges=[1.0] * 3)
    scan.header.frame_id = "laser"
    display = displays.LaserScan()
    first = build(display, scan).batches[0]
    assert build(display).batches[0] is first  # nothing changed: the same arrays
    TREE.offsets["laser"] = ("odom", (0.0, 3.0, 0.0))
    try:
        moved = build(display).batches[0]
        assert moved is not first and moved.vertices[0] == pytest.approx([2, 3, 0])
    finally:
        TREE.offsets["laser"] = ("odom", (0.0, 2.0, 0.0))
    display.options["Color"] = "0; 0; 255"
    assert build(display).batches[0].colors[0][:3] == pytest.approx([0, 0, 1])
    again = build(display, scan).batches[0]
    assert build(display).batches[0] is again


URDF = """<robot name="r">
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <link name="odom"><visual><origin xyz="0 0 0.5" rpy="0 0 1.5707963"/>
    <geometry><box size="2 1 1"/></geometry><material name="blue"/></visual></link>
  <link name="laser"><visual><geometry><cylinder radius="0.5" length="0.2"/></geometry></visual>
    <visual><geometry><mesh filename="package://r/base.dae"/></geometry></visual></link>
  <link name="wheel"><visual><geometry><sphere radius="0.1"/></geometry></visual></link>
</robot>"""


def test_robot_model_places_the_urdf_visuals_at_their_links() -> None:
    from kame.rviz.robot import RobotModel

    display = RobotModel()
    display.describe(URDF)
    scene = build(display)
    triangles = scene.batches[0]  # the box's 36 vertices, then the cylinder's (one batch)
    box = triangles.vertices[:36]
    # the box turned a quarter about z, lifted 0.5 m, at odom (1, 0, 0): x spans 1 m, y 2 m
    assert box.min(axis=0) == pytest.approx([0.5, -1, 0], abs=1e-6)
    assert box.max(axis=0) == pytest.approx([1.5, 1, 1], abs=1e-6)
    assert triangles.colors[0] == pytest.approx([0, 0, 1, 1])
    cylinder = triangles.vertices[36:]
    assert cylinder.min(axis=0) == pytest.approx([0.5, 1.5, -0.1], abs=1e-6)
    assert triangles.colors[-1] == pytest.approx([1, 0, 0, 1])  # rviz's red for a part with no material
    assert display.status.level == WARN
    assert "wheel: no transform from wheel to map" in display.status.text
    assert "laser: package [r] not found for package://r/base.dae" in display.status.text
    display.describe(None)
    build(display)
    assert "parameter robot_description is not set" in display.status.text
    display.describe("<robot><link name='a'>")
    build(display)
    assert "not XML" in display.status.text


def test_a_display_draws_once_tf_has_the_frame_it_lacked() -> None:
    grid = displays.Grid()
    tree = TreeOf("map", {})
    grid.build(Scene(), TreeOf("map", {"odom": ("base", (0, 0, 0))}), 0.0)
    assert grid.status.level == OK  # the fixed frame itself needs no tf
    grid.options["Reference Frame"] = "odom"
    grid.build(Scene(), tree, 0.0)
    assert grid.status.level == WARN and "odom" in grid.status.text
    scene = Scene()
    grid.build(scene, TreeOf("map", {"odom": ("map", (2.0, 0, 0))}), 0.0)  # the cached scene is not reused
    assert grid.status.level == OK and scene.batches


def test_the_grid_is_centred_on_its_offset() -> None:
    # turtle_rviz.rviz: 11 cells of 1 m around (5.5, 5.5), turtlesim's world
    scene = build(displays.Grid(options={"Plane Cell Count": 11, "Offset": {"X": 5.5, "Y": 5.5, "Z": 0}}))
    points = all_vertices(scene)
    assert points[:, 0].min() == pytest.approx(0.0) and points[:, 0].max() == pytest.approx(11.0)
    assert points[:, 1].min() == pytest.approx(0.0) and points[:, 1].max() == pytest.approx(11.0)


def _mesh_package(tmp_path):  # type: ignore[no-untyped-def]
    """A package `parts` holding a 1 x 2 x 3 box as binary STL, ASCII STL and red Collada."""
    trimesh = pytest.importorskip("trimesh", reason="rviz reads meshes with trimesh (kame[gui])")
    pytest.importorskip("collada", reason="Collada files are read through pycollada (kame[gui])")
    box = trimesh.creation.box((1.0, 2.0, 3.0))
    box.visual.face_colors = [255, 0, 0, 255]
    meshes = tmp_path / "parts" / "meshes"
    meshes.mkdir(parents=True)
    (meshes / "box.stl").write_bytes(box.export(file_type="stl"))
    (meshes / "box_ascii.stl").write_text(box.export(file_type="stl_ascii"))
    (meshes / "box.dae").write_bytes(box.export(file_type="dae"))
    from kame.rviz.meshes import MeshLibrary

    return MeshLibrary(lambda name: str(tmp_path / name) if name == "parts" else None)


def test_mesh_resources_are_read_from_stl_and_collada_through_package_urls(tmp_path) -> None:  # type: ignore[no-untyped-def]
    library = _mesh_package(tmp_path)
    for name in ("box.stl", "box_ascii.stl", "box.dae"):
        mesh = library.load(f"package://parts/meshes/{name}")
        assert not isinstance(mesh, str), mesh
        assert mesh.triangles.shape == (36, 3)
        assert mesh.triangles.min(axis=0) == pytest.approx([-0.5, -1, -1.5])
    dae = library.load("package://parts/meshes/box.dae")
    assert not isinstance(dae, str) and dae.colors is not None and dae.colors[0] == pytest.approx([1, 0, 0, 1])
    assert library.load(f"file://{tmp_path}/parts/meshes/box.stl") is not None
    assert "package [nowhere] not found" in str(library.load("package://nowhere/box.stl"))
    assert "No such file" in str(library.load("package://parts/meshes/missing.stl"))
    (tmp_path / "parts" / "meshes" / "broken.dae").write_text("<COLLADA>")
    assert "cannot read mesh" in str(library.load("package://parts/meshes/broken.dae"))


def test_a_mesh_marker_and_a_urdf_mesh_visual_are_drawn_scaled_and_placed(tmp_path) -> None:  # type: ignore[no-untyped-def]
    from kame.rviz.robot import RobotModel

    library = _mesh_package(tmp_path)
    display = markers.Marker()
    display.meshes = library
    marker = Marker(type=markers.MESH, action=markers.ADD, mesh_resource="package://parts/meshes/box.stl")
    marker.header.frame_id = "odom"
    marker.pose.orientation.w = 1.0
    marker.scale.x = marker.scale.y = marker.scale.z = 2.0
    marker.color.g = marker.color.a = 1.0
    scene = build(display, marker)
    assert display.status.level == OK, display.status.text
    assert all_vertices(scene).min(axis=0) == pytest.approx([0, -2, -3])  # odom at x = 1
    assert scene.batches[0].colors[0] == pytest.approx([0, 1, 0, 1])
    marker.mesh_use_embedded_materials, marker.mesh_resource = True, "package://parts/meshes/box.dae"
    assert build(display, marker).batches[0].colors[0] == pytest.approx([1, 0, 0, 1])  # the file's red
    robot = RobotModel()
    robot.meshes = library
    robot.describe('<robot name="r"><link name="laser"><visual><origin xyz="0 0 1"/><geometry>'
                   '<mesh filename="package://parts/meshes/box.dae" scale="1 1 0.5"/></geometry></visual></link>'
                   '</robot>')
    drawn = build(robot)
    assert robot.status.level == OK, robot.status.text
    assert all_vertices(drawn).min(axis=0) == pytest.approx([0.5, 1, 0.25])  # laser at (1, 2, 0)
    assert drawn.batches[0].colors[0] == pytest.approx([1, 0, 0, 1])  # no URDF material: the mesh's colour


def test_solid_markers_drawn_together_match_each_drawn_alone() -> None:
    rng = np.random.default_rng(3)
    for kind in markers.SOLIDS:
        array = MarkerArray()
        for i in range(6):
            marker = Marker(ns="n", id=i, type=kind, action=markers.ADD)
            marker.header.frame_id = ("odom", "laser")[i % 2]
            marker.pose.position = Point(*rng.uniform(-3, 3, 3))
            marker.pose.orientation = Quaternion(*rng.normal(size=4))  # not normalised: rviz normalises
            marker.scale.x, marker.scale.y, marker.scale.z = rng.uniform(0.1, 2, 3)
            marker.color.r, marker.color.a = i / 6, 1.0
            array.markers.append(marker)
        together = build(markers.MarkerArray(), array).batches[0].unindexed()  # shared vertices written out
        if kind == markers.ARROW:  # a shaft and head about the pose's x, scale.x long, tip at the end
            for i, marker in enumerate(array.markers):
                m = TREE.transform(marker.header.frame_id) @ pose_matrix(marker.pose)
                tail, tip = m[:3, 3], m[:3, 3] + m[:3, 0] * marker.scale.x
                arrow = together.vertices[120 * i:120 * (i + 1)]  # 8 sides of 4 triangles, a cap of 8
                along = (arrow - tail) @ m[:3, 0]
                across = np.linalg.norm(arrow - tail - np.outer(along, m[:3, 0]), axis=1)
                assert along.min() == pytest.approx(0, abs=1e-5) and along.max() == pytest.approx(marker.scale.x)
                assert across.max() == pytest.approx(marker.scale.y, rel=1e-5)  # the head: twice the shaft
                assert np.linalg.norm(arrow - tip, axis=1).min() == pytest.approx(0, abs=1e-5)
            continue
        shape = {markers.CUBE: box_triangles, markers.SPHERE: sphere_triangles,
                 markers.CYLINDER: cylinder_triangles}[kind]
        alone = [apply(TREE.transform(m.header.frame_id) @ pose_matrix(m.pose), shape((m.scale.x, m.scale.y,
                                                                                      m.scale.z)))
                 for m in array.markers]
        alone = [without_flat(shape) for shape in alone]  # the sphere's at its poles are not drawn
        assert unwound(together.vertices) == pytest.approx(unwound(np.concatenate(alone)), abs=1e-5)
        assert together.float_colors()[::len(alone[0])] == pytest.approx(
            np.array([(i / 6, 0, 0, 1) for i in range(6)]), abs=1 / 255)  # bytes
        # drawn with the faces turned away culled: each must wind counter-clockwise seen from outside
        assert together.closed
        triangles = together.vertices.reshape(-1, 3, 3).astype(float)
        centres = np.repeat([apply(TREE.transform(m.header.frame_id), [[m.pose.position.x, m.pose.position.y,
                                                                        m.pose.position.z]])[0]
                             for m in array.markers], len(alone[0]) // 3, axis=0)
        facing = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
        assert ((facing * (triangles.mean(axis=1) - centres)).sum(axis=1) >= -1e-6).all()
        assert (np.einsum("ij,ij->i", together.normals, np.repeat(facing, 3, axis=0)) >= -1e-6).all()


def test_solids_share_their_vertices_and_stay_so_when_merged() -> None:
    for kind in markers.SOLIDS:
        vertices, normals, indices = markers.solid_template(kind)
        assert len(vertices) <= indices.size * 2 / 3  # a cube's 24 corners for 36: a face's two triangles share 2
        assert set(indices.ravel().tolist()) == set(range(len(vertices)))  # each vertex used
        assert np.linalg.norm(normals, axis=1) == pytest.approx(1, abs=1e-6)
    sphere = markers.solid_template(markers.SPHERE)
    assert (np.einsum("ij,ij->i", sphere[0], sphere[1]) > 0.49).all()  # smooth: each normal along its radius
    array = MarkerArray()
    for i, kind in enumerate((markers.CUBE, markers.SPHERE)):
        marker = Marker(ns="n", id=i, type=kind, action=markers.ADD)
        marker.header.frame_id = "odom"
        marker.pose.position.x, marker.pose.orientation.w = 3.0 * i, 1.0
        marker.scale.x = marker.scale.y = marker.scale.z = 1.0
        marker.color.g = marker.color.a = 1.0
        array.markers.append(marker)
    apart = Scene()
    for marker in array.markers:  # drawn alone: a batch each
        apart.extend(build(markers.Marker(), marker))
    assert len(apart.batches) == 2 and all(b.indices is not None for b in apart.batches)
    merged = apart.merged()
    assert len(merged.batches) == 1
    written = np.concatenate([b.unindexed().vertices for b in apart.batches])
    assert merged.batches[0].unindexed().vertices == pytest.approx(written)
    assert merged.batches[0].unindexed().normals == pytest.approx(
        np.concatenate([b.unindexed().normals for b in apart.batches]))
    with pytest.raises(ValueError, match="normals"):  # the window could not work them out from shared vertices
        Scene().add("triangles", np.eye(3), (1.0, 1.0, 1.0, 1.0), indices=np.array([0, 1, 2]))


def test_an_option_typed_into_the_panel_keeps_the_kind_of_value_it_had() -> None:
    assert edited_option(1, "0.5") == 0.5  # a Cell Size of 1 made half as big
    assert edited_option(10, "4") == 4 and isinstance(edited_option(10, "4"), int)
    assert edited_option(10, "4.0") == 4 and isinstance(edited_option(10, "4.0"), int)
    assert edited_option(0.5, "2") == 2.0 and isinstance(edited_option(0.5, "2"), float)
    assert edited_option(1, "many") == "many"  # kept as typed: the display reads its default then
    assert edited_option(True, "0") == "0" and not displays.Grid(options={"Show": "0"}).flag("Show")
    assert edited_option("/scan", "/base_scan") == "/base_scan"
