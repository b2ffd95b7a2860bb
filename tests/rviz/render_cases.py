"""One small scene per display type, each with a point of the fixed frame where the display must
colour the view and the colour it must have there; rendered by render_child under Xvfb."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from geometry_msgs.msg import Point, Point32, PointStamped, Pose, PoseArray, PoseStamped, Quaternion, Vector3
from kame.rviz import displays, markers
from kame.rviz.display import Display
from nav_msgs.msg import OccupancyGrid, Odometry, Path
from sensor_msgs.msg import LaserScan, PointCloud2, PointField
from std_msgs.msg import ColorRGBA
from visualization_msgs.msg import Marker, MarkerArray

IDENTITY = Quaternion(0, 0, 0, 1)


class Frames:
    """map at the origin; laser 2 m along x, turned a quarter to the left."""

    fixed_frame = "map"

    def transform(self, frame_id: str) -> np.ndarray | str:
        if frame_id == "map":
            return np.eye(4)
        if frame_id == "laser":
            m = np.eye(4)
            m[:3, :3] = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]
            m[0, 3] = 2.0
            return m
        return f"no transform from {frame_id} to map"

    def names(self) -> list[str]:
        return ["map", "laser"]

    def parent(self, frame_id: str) -> str | None:
        return "map" if frame_id == "laser" else None


@dataclass
class Case:
    name: str
    make: Callable[[], tuple[Display, list[Any]]]
    probe: tuple[float, float, float]  # a fixed-frame point the display covers
    color: tuple[int, int, int]  # what the pixel there must be (within a tolerance)
    offset: tuple[int, int] = (0, 0)  # pixels from the probe's: text is drawn up and right of its point


def _scan() -> tuple[Display, list[Any]]:
    scan = LaserScan(angle_min=-0.1, angle_increment=0.01, range_min=0.1, range_max=10.0, ranges=[1.0] * 21)
    scan.header.frame_id = "laser"  # the rays point along the laser's x: the map's y
    return displays.LaserScan(options={"Color": "255; 0; 0", "Style": "Points", "Size (Pixels)": 6}), [scan]


def _cloud() -> tuple[Display, list[Any]]:
    points = np.zeros(25, dtype=[("x", "<f4"), ("y", "<f4"), ("z", "<f4")])
    points["x"] = -2 + np.repeat(np.linspace(-0.04, 0.04, 5), 5)
    points["y"] = -1 + np.tile(np.linspace(-0.04, 0.04, 5), 5)
    fields = [PointField(name=n, offset=4 * i, datatype=7, count=1) for i, n in enumerate("xyz")]
    cloud = PointCloud2(height=1, width=25, fields=fields, point_step=12, row_step=300, data=points.tobytes())
    cloud.header.frame_id = "map"
    return displays.PointCloud2(options={"Color": "0; 255; 255", "Style": "Points", "Size (Pixels)": 6}), [cloud]


def _intensity_scan() -> tuple[Display, list[Any]]:
    """rviz's default for a scan with intensities: the rainbow, the strongest rays magenta; the
    weakest (red, at the rays' other end) bound it."""
    scan = LaserScan(angle_min=-0.1, angle_increment=0.01, range_min=0.1, range_max=10.0, ranges=[2.0] * 21,
                     intensities=[0.0] * 10 + [100.0] * 11)
    scan.header.frame_id = "laser"  # 2 m along the map's y from (2, 0), the strong rays to its left
    return displays.LaserScan(options={"Style": "Points", "Size (Pixels)": 6}), [scan]


def _square_cloud() -> tuple[Display, list[Any]]:
    """rviz's default style: squares "Size (m)" wide where they are, here 0.3 m: 15 pixels."""
    points = np.zeros(1, dtype=[("x", "<f4"), ("y", "<f4"), ("z", "<f4")])
    points["x"], points["y"] = 2.0, -1.0
    fields = [PointField(name=n, offset=4 * i, datatype=7, count=1) for i, n in enumerate("xyz")]
    cloud = PointCloud2(height=1, width=1, fields=fields, point_step=12, row_step=12, data=points.tobytes())
    cloud.header.frame_id = "map"
    return displays.PointCloud2(options={"Color": "255; 255; 0", "Size (m)": 0.3}), [cloud]


def _rgb_cloud() -> tuple[Display, list[Any]]:
    """Colours from the cloud's packed rgb field (uploaded as bytes)."""
    points = np.zeros(25, dtype=[("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("rgb", "<u4")])
    points["x"] = -1 + np.repeat(np.linspace(-0.04, 0.04, 5), 5)
    points["y"] = 0.5 + np.tile(np.linspace(-0.04, 0.04, 5), 5)
    points["rgb"] = 0xFF8000
    fields = [PointField(name=n, offset=4 * i, datatype=7, count=1) for i, n in enumerate(("x", "y", "z", "rgb"))]
    cloud = PointCloud2(height=1, width=25, fields=fields, point_step=16, row_step=400, data=points.tobytes())
    cloud.header.frame_id = "map"
    return displays.PointCloud2(options={"Style": "Points", "Size (Pixels)": 6}), [cloud]


def _grid() -> tuple[Display, list[Any]]:
    grid = OccupancyGrid(data=[0] * 100)
    grid.header.frame_id = "map"
    grid.info.width = grid.info.height = 10
    grid.info.resolution = 0.1
    grid.info.origin = Pose(position=Point(-3, 1, 0), orientation=IDENTITY)
    return displays.OccupancyGrid(options={"Alpha": 1.0}), [grid]


def _marker(kind: int, **extra: Any) -> Marker:
    marker = Marker(ns="test", id=kind, type=kind, pose=Pose(position=Point(1, -2, 0), orientation=IDENTITY))
    marker.header.frame_id = "map"
    marker.scale.x = marker.scale.y = marker.scale.z = 0.5
    marker.color.b = marker.color.a = 1.0
    for key, value in extra.items():
        setattr(marker, key, value)
    return marker


def _marker_case(kind: int, **extra: Any) -> Callable[[], tuple[Display, list[Any]]]:
    return lambda: (markers.Marker(), [_marker(kind, **extra)])


QUARTER_TURN = Quaternion(0, 0, math.sin(math.pi / 4), math.cos(math.pi / 4))


def _cube_list() -> tuple[Display, list[Any]]:
    """The cubes' points are in the marker's frame: turned a quarter, (0.5, 0) is 0.5 m along
    the map's y from the pose at (1, -2); none is at the pose itself."""
    cubes = _marker(markers.CUBE_LIST, pose=Pose(position=Point(1, -2, 0), orientation=QUARTER_TURN),
                    points=[Point(-0.5, 0, 0), Point(0.5, 0, 0)], scale=Vector3(0.3, 0.3, 0.3))
    return markers.Marker(), [cubes]


def _sphere_list() -> tuple[Display, list[Any]]:
    """Each sphere in its own colour (colors, one a point): the second one green, 0.5 m right of the pose."""
    spheres = _marker(markers.SPHERE_LIST, points=[Point(-0.5, 0, 0), Point(0.5, 0, 0)], scale=Vector3(0.3, 0.3, 0.3),
                      colors=[ColorRGBA(1, 0, 0, 1), ColorRGBA(0, 1, 0, 1)])
    return markers.Marker(), [spheres]


# two segments, one a pair of points, 20 pixels wide: the lower from (0.5, -2.5) to (1.5, -2.5)
# and the upper from (0.5, -1.5) to (1.5, -1.5); a strip would also join (1.5, -2.5) to (0.5, -1.5)
LINE_LIST_POINTS = [Point(-0.5, -0.5, 0), Point(0.5, -0.5, 0), Point(-0.5, 0.5, 0), Point(0.5, 0.5, 0)]


def _line_list() -> tuple[Display, list[Any]]:
    return markers.Marker(), [_marker(markers.LINE_LIST, points=LINE_LIST_POINTS, scale=Vector3(0.2, 0, 0))]


def _text_over_a_cube() -> tuple[Display, list[Any]]:
    """Text is drawn over the scene, never hidden by what is nearer the camera."""
    text = _marker(markers.TEXT, text="MMMM")
    text.color.r = text.color.g = 1.0
    cube = _marker(markers.CUBE, pose=Pose(position=Point(1, -2, 1), orientation=IDENTITY))
    return markers.MarkerArray(), [MarkerArray(markers=[cube, text])]


def _marker_array() -> tuple[Display, list[Any]]:
    array = MarkerArray(markers=[_marker(markers.CUBE, id=i, pose=Pose(position=Point(-2 + 0.2 * i, 2, 0),
                                                                       orientation=IDENTITY)) for i in range(5)])
    for marker in array.markers:
        marker.scale.x = marker.scale.y = marker.scale.z = 0.15
    return markers.MarkerArray(), [array]


def _pose() -> tuple[Display, list[Any]]:
    pose = PoseStamped(pose=Pose(position=Point(0, 0, 0), orientation=Quaternion(0, 0, math.sin(math.pi / 4),
                                                                                 math.cos(math.pi / 4))))
    pose.header.frame_id = "map"  # points along the map's y
    return displays.Pose(options={"Color": "255; 255; 0"}), [pose]


def _odometry() -> tuple[Display, list[Any]]:
    odometry = Odometry()
    odometry.header.frame_id = "laser"  # along the laser's x: the map's +y from (2, 0)
    odometry.pose.pose.orientation = IDENTITY
    return displays.Odometry(options={"Shape": {"Color": "255; 0; 255"}}), [odometry]


def _path() -> tuple[Display, list[Any]]:
    path = Path(poses=[PoseStamped(pose=Pose(position=Point(x, -1, 0), orientation=IDENTITY)) for x in (-1, 1)])
    path.header.frame_id = "map"
    return displays.Path(options={"Color": "0; 255; 0", "Line Width": 5}), [path]


def _pose_array() -> tuple[Display, list[Any]]:
    array = PoseArray(poses=[Pose(position=Point(-1, -2, 0), orientation=IDENTITY)])
    array.header.frame_id = "map"
    return displays.PoseArray(options={"Color": "255; 0; 0", "Arrow Length": 1.0}), [array]


def _point() -> tuple[Display, list[Any]]:
    point = PointStamped(point=Point(-2, -2, 0))
    point.header.frame_id = "map"
    return displays.PointStamped(options={"Color": "255; 128; 0", "Radius": 0.2}), [point]


def _polygon() -> tuple[Display, list[Any]]:
    from geometry_msgs.msg import PolygonStamped

    polygon = PolygonStamped()
    polygon.header.frame_id = "map"
    polygon.polygon.points = [Point32(-1, 1, 0), Point32(1, 1, 0), Point32(1, 2, 0)]
    return displays.Polygon(options={"Color": "0; 0; 255"}), [polygon]


def _robot() -> tuple[Display, list[Any]]:
    from kame.rviz.robot import RobotModel

    robot = RobotModel()
    robot.describe('<robot name="r"><link name="laser"><visual><origin xyz="0 1 0"/>'
                   '<geometry><box size="0.4 0.4 0.4"/></geometry><material name="m"><color rgba="1 0 0 1"/>'
                   '</material></visual></link></robot>')
    return robot, []


def _range() -> tuple[Display, list[Any]]:
    from kame.rviz.sensors import Range as RangeDisplay
    from sensor_msgs.msg import Range

    cone = Range(field_of_view=0.5, min_range=0.1, max_range=2.0, range=1.0)
    cone.header.frame_id = "laser"  # along the laser's x: the map's +y from (2, 0)
    return RangeDisplay(options={"Color": "0; 255; 0", "Alpha": 1}), [cone]


def _wrench() -> tuple[Display, list[Any]]:
    from geometry_msgs.msg import WrenchStamped
    from kame.rviz.sensors import WrenchStamped as WrenchDisplay

    wrench = WrenchStamped()
    wrench.header.frame_id = "map"
    wrench.wrench.force.y = 0.5  # an arrow from the origin to (0, 1)
    return WrenchDisplay(options={"Force Color": "255; 0; 0"}), [wrench]


def _mesh() -> tuple[Display, list[Any]]:
    """A binary STL box (read once: the display's library keeps it after the file is gone)."""
    import os
    import tempfile

    import trimesh

    from kame.rviz.meshes import MeshLibrary

    handle, path = tempfile.mkstemp(suffix=".stl")
    try:
        os.write(handle, trimesh.creation.box((0.5, 0.5, 0.5)).export(file_type="stl"))
        os.close(handle)
        display = markers.Marker()
        display.meshes = MeshLibrary()
        display.meshes.load(f"file://{path}")
    finally:
        os.unlink(path)
    return display, [_marker(markers.MESH, mesh_resource=f"file://{path}")]


CASES = [
    Case("LaserScan", _scan, (2.0, 1.0, 0.0), (255, 0, 0)),
    Case("LaserScan intensity", _intensity_scan, (1.9, 2.0, 0.0), (255, 0, 255)),
    Case("PointCloud2", _cloud, (-2.0, -1.0, 0.0), (0, 255, 255)),
    Case("PointCloud2 squares", _square_cloud, (2.0, -1.0, 0.0), (255, 255, 0), (6, 0)),
    Case("PointCloud2 rgb", _rgb_cloud, (-1.0, 0.5, 0.0), (255, 128, 0)),
    Case("Map", _grid, (-2.5, 1.5, 0.0), (255, 255, 255)),
    Case("Marker cube", _marker_case(markers.CUBE), (1.0, -2.0, 0.0), (0, 0, 255)),
    Case("Marker sphere", _marker_case(markers.SPHERE), (1.0, -2.0, 0.0), (0, 0, 255)),
    Case("Marker cylinder", _marker_case(markers.CYLINDER), (1.0, -2.0, 0.0), (0, 0, 255)),
    Case("Marker arrow", _marker_case(markers.ARROW), (1.25, -2.0, 0.0), (0, 0, 255)),
    Case("Marker points", _marker_case(markers.POINTS, points=[Point(0, 0, 0)]), (1.0, -2.0, 0.0), (0, 0, 255)),
    Case("Marker line strip", _marker_case(markers.LINE_STRIP, points=[Point(-0.5, 0, 0), Point(0.5, 0, 0)]),
         (1.0, -2.0, 0.0), (0, 0, 255)),
    Case("Marker triangle list", _marker_case(markers.TRIANGLES, points=[Point(-0.5, -0.5, 0), Point(0.5, -0.5, 0),
                                                                         Point(0, 0.5, 0)]),
         (1.0, -2.0, 0.0), (0, 0, 255)),
    Case("Marker cube list", _cube_list, (1.0, -1.5, 0.0), (0, 0, 255)),
    Case("Marker sphere list", _sphere_list, (1.5, -2.0, 0.0), (0, 255, 0)),
    Case("Marker line list", _line_list, (1.25, -1.5, 0.0), (0, 0, 255)),
    Case("Marker line list lower", _line_list, (0.75, -2.5, 0.0), (0, 0, 255)),
    Case("Marker line list gap", _line_list, (1.0, -2.0, 0.0), (51, 51, 51)),  # nothing between the pairs
    Case("Marker text", _text_over_a_cube, (1.0, -2.0, 0.0), (255, 255, 255), (6, -8)),
    Case("MarkerArray", _marker_array, (-1.6, 2.0, 0.0), (0, 0, 255)),
    Case("Pose", _pose, (0.0, 0.5, 0.0), (255, 255, 0)),
    Case("Odometry", _odometry, (2.0, 0.5, 0.0), (255, 0, 255)),
    Case("Path", _path, (0.0, -1.0, 0.0), (0, 255, 0)),
    Case("PoseArray", _pose_array, (-0.5, -2.0, 0.0), (255, 0, 0)),
    Case("PointStamped", _point, (-2.0, -2.0, 0.0), (255, 128, 0)),
    Case("Polygon", _polygon, (0.0, 1.0, 0.0), (0, 0, 255)),
    Case("Axes", lambda: (displays.Axes(options={"Reference Frame": "laser"}), []), (2.0, 0.5, 0.0), (255, 0, 0)),
    Case("Grid", lambda: (displays.Grid(options={"Color": "255; 255; 255", "Alpha": 1}), []), (0.0, 1.5, 0.0),
         (255, 255, 255)),
    Case("RobotModel", _robot, (1.0, 0.0, 0.0), (255, 0, 0)),  # the laser's y is the map's -x
    Case("Range", _range, (2.0, 0.8, 0.0), (0, 255, 0)),
    Case("WrenchStamped", _wrench, (0.0, 0.4, 0.0), (255, 0, 0)),
    Case("Marker mesh", _mesh, (1.0, -2.0, 0.0), (0, 0, 255)),
    Case("TF", lambda: (displays.TF(options={"Show Names": False}), []), (2.0, 0.15, 0.0), (255, 0, 0)),
]
