"""rviz's displays of the course, as the scene they make in the fixed frame: Grid, Axes, TF,
LaserScan, PointCloud2, Odometry, Pose, PoseArray, PointStamped, Path, Polygon and
OccupancyGrid (map and costmap colour schemes). Markers are in kame.rviz.markers."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from kame.rviz.colors import point_colors
from kame.rviz.display import WARN, Display, Frames, Selectable, Status, coordinates, parse_color
from kame.rviz.scene import Scene, apply, arrow_triangles, axes_lines, pose_matrix, spatial_order, sphere_triangles

FLOAT32 = 7
SPATIAL_ORDER_FROM = 10_000  # points: a cloud this big is drawn box by box (scene.spatial_order)
FIELD_DTYPES = {1: "i1", 2: "u1", 3: "i2", 4: "u2", 5: "i4", 6: "u4", 7: "f4", 8: "f8"}


class Grid(Display):
    class_name = "rviz/Grid"
    defaults = {"Cell Size": 1, "Plane Cell Count": 10, "Color": "160; 160; 164", "Alpha": 0.5,
                "Reference Frame": "<Fixed Frame>"}

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        placed = self.placed(frames, self.reference_frame(frames))
        if placed is None:
            return
        count = max(1, int(self.number("Plane Cell Count", 10)))
        cell = self.number("Cell Size", 1.0)
        half = count * cell / 2
        ticks = np.linspace(-half, half, count + 1)
        lines = [[(t, -half, 0), (t, half, 0)] for t in ticks] + [[(-half, t, 0), (half, t, 0)] for t in ticks]
        offset = self.options.get("Offset")  # rviz's: the grid's centre in its reference frame
        shift = [float(offset.get(axis, 0)) for axis in "XYZ"] if isinstance(offset, dict) else [0.0, 0.0, 0.0]
        scene.add("lines", apply(placed, np.array(lines) + shift), self.color(), self.number("Line Width", 1))


class Axes(Display):
    class_name = "rviz/Axes"
    defaults = {"Length": 1, "Radius": 0.1, "Reference Frame": "<Fixed Frame>"}

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        placed = self.placed(frames, self.reference_frame(frames))
        if placed is not None:
            axes_lines(scene, placed, self.number("Length", 1.0), width=max(2.0, self.number("Radius", 0.1) * 30))


class TF(Display):
    """Every frame's axes, its name, and an arrow from it to its parent (rviz's yellow-to-pink)."""
    class_name = "rviz/TF"
    defaults = {"Show Axes": True, "Show Names": True, "Show Arrows": True, "Marker Scale": 1}

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        scale = self.number("Marker Scale", 1.0)
        missing = []
        origins: dict[str, np.ndarray] = {}
        for frame in frames.names():
            placed = frames.transform(frame)
            if isinstance(placed, str):
                missing.append(frame)
                continue
            origins[frame] = placed[:3, 3]
            if self.flag("Show Axes"):
                axes_lines(scene, placed, 0.3 * scale, width=2)
            if self.flag("Show Names"):
                scene.label(placed[:3, 3], frame, (1, 1, 1, 1))
        if self.flag("Show Arrows"):
            segments, colors = [], []
            for frame, origin in origins.items():
                parent = frames.parent(frame)
                if parent in origins:
                    segments += [origin, origins[parent]]
                    colors += [(1, 1, 0, 1), (1, 0, 1, 1)]
            scene.add("lines", segments, colors, 1.5)
        if missing:
            self.status = Status(WARN, f"no transform to {frames.fixed_frame} from {', '.join(sorted(missing))}")


class PointCloudCommon(Display):
    """What rviz's LaserScan and PointCloud2 share: the points of each message in the fixed
    frame, coloured by a colour transformer (kame.rviz.colors), "Size (Pixels)" wide in the
    Points style, else (Squares, Flat Squares and, drawn as those, Spheres and Boxes) "Size (m)"
    wide where they are; with a
    "Decay Time" (seconds) every message received in that time stays drawn, each through tf
    as it is now."""
    defaults = {"Style": "Flat Squares", "Size (m)": 0.01, "Size (Pixels)": 3, "Color": "255; 255; 255", "Alpha": 1,
                "Color Transformer": "",
                "Decay Time": 0, "Channel Name": "intensity", "Use rainbow": True, "Invert Rainbow": False,
                "Min Color": "0; 0; 0", "Max Color": "255; 255; 255", "Autocompute Intensity Bounds": True,
                "Axis": "Z", "Use Fixed Frame": True}

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.kept: list[tuple[float, Any]] = []  # (received, message), oldest first, while they decay
        # each message's points drawn last (fixed frame), their indices in it (None: all), its fields
        self._drawn: list[tuple[np.ndarray, np.ndarray | None, dict[str, np.ndarray]]] = []

    def receive(self, messages: Any, now: float) -> None:
        decay = self.number("Decay Time", 0.0)
        for message in messages:
            self.message = message
            self.version += 1
            self.kept = [*self.kept, (now, message)] if decay > 0 else [(now, message)]

    def reset(self) -> None:
        super().reset()
        self.kept = []
        self._drawn = []

    def points(self, message: Any) -> tuple[np.ndarray, dict[str, np.ndarray]] | str:
        """The message's points (N x 3 float32, its own frame, NaN where none) and its fields,
        one value a point; or why it has none."""
        raise NotImplementedError

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        decay = self.number("Decay Time", 0.0)
        if decay > 0:  # rviz drops every cloud older than the decay time, the newest too
            self.kept = [(at, m) for at, m in self.kept if now - at <= decay]
            self.expires_at = min((at + decay for at, _ in self.kept), default=math.inf)
        self._drawn = []
        for _, message in self.kept if decay > 0 else [(now, self.message)]:
            placed = self.placed(frames, message.header.frame_id)
            if placed is None:
                continue
            found = self.points(message)
            if isinstance(found, str):
                self.status = Status(WARN, found)
                continue
            local, fields = found
            colors = point_colors(self.options, fields, placed, local, self.color())
            # a NaN or infinite coordinate makes the sum one: 30x faster than all(axis=1) over 3 columns
            finite = np.isfinite(local[:, 0] + local[:, 1] + local[:, 2])
            indices = None
            if not finite.all():
                local, indices = local[finite], np.flatnonzero(finite)
                colors = colors[finite] if isinstance(colors, np.ndarray) else colors
            fixed = apply(placed, local)
            if len(fixed) >= SPATIAL_ORDER_FROM:
                order = spatial_order(fixed)
                fixed = np.take(fixed, order, axis=0)  # take: 8x faster than fancy indexing here
                colors = np.take(colors, order, axis=0) if isinstance(colors, np.ndarray) else colors
                indices = order if indices is None else indices[order]
            if self.options.get("Style") == "Points":
                scene.add("points", fixed, colors, self.number("Size (Pixels)", 3))
            else:
                scene.add("points", fixed, colors, self.number("Size (m)", 0.01), metres=True)
            self._drawn.append((fixed, indices, fields))

    def selectable(self) -> Selectable | None:
        """Every point drawn: "Point <its index in the message>", its position and fields."""
        if not self._drawn:
            return None
        parts = self._drawn
        starts = np.cumsum([0] + [len(fixed) for fixed, _, _ in parts])

        def describe(i: int) -> tuple[str, dict[str, str]]:
            part = int(np.searchsorted(starts, i, side="right")) - 1
            fixed, indices, fields = parts[part]
            row = i - int(starts[part])
            index = row if indices is None else int(indices[row])
            properties = {"Position": coordinates(fixed[row])}
            properties.update({name: f"{values[index]:.6g}" for name, values in fields.items()
                               if name not in ("x", "y", "z")})
            return f"Point {index}", properties

        return Selectable(np.concatenate([fixed for fixed, _, _ in parts]), describe)


class LaserScan(PointCloudCommon):
    """A scan's ranges as points; its intensities (when it has one a range) are the
    "intensity" channel, as laser_geometry makes it for rviz."""
    class_name = "rviz/LaserScan"
    message_types = ("sensor_msgs/LaserScan",)
    defaults = {**PointCloudCommon.defaults, "Topic": "/scan", "Color": "255; 0; 0"}

    def points(self, message: Any) -> tuple[np.ndarray, dict[str, np.ndarray]] | str:
        ranges = np.asarray(message.ranges, dtype=np.float32)
        angles = message.angle_min + message.angle_increment * np.arange(len(ranges))
        valid = np.isfinite(ranges) & (ranges >= message.range_min) & (ranges <= message.range_max)
        shown = np.where(valid, ranges, np.nan).astype(np.float32)
        local = np.column_stack([shown * np.cos(angles), shown * np.sin(angles), np.where(valid, 0.0, np.nan)])
        fields = {}
        if len(message.intensities) == len(ranges):
            # a ray out of range is no point: its intensity bounds nothing (laser_geometry drops it)
            fields["intensity"] = np.where(valid, np.asarray(message.intensities, dtype=np.float32), np.nan)
        return local.astype(np.float32), fields


def cloud_array(cloud: Any) -> np.ndarray:
    """A sensor_msgs/PointCloud2's points as a structured array of its fields."""
    endian = ">" if cloud.is_bigendian else "<"
    names, formats, offsets = [], [], []
    for point_field in cloud.fields:
        if point_field.datatype in FIELD_DTYPES and point_field.count >= 1:
            names.append(point_field.name)
            formats.append(endian + FIELD_DTYPES[point_field.datatype])
            offsets.append(point_field.offset)
    dtype = np.dtype({"names": names, "formats": formats, "offsets": offsets, "itemsize": cloud.point_step})
    data = cloud.data  # bytes, or a numpy array over the received ones (kame.rviz.source.decode)
    rows = (np.asarray(data, dtype=np.uint8) if isinstance(data, (list, tuple)) else
            np.frombuffer(data, dtype=np.uint8))[: cloud.row_step * cloud.height]
    rows = rows.reshape(cloud.height, cloud.row_step)[:, : cloud.point_step * cloud.width]
    return np.ascontiguousarray(rows).view(dtype).reshape(-1)


class PointCloud2(PointCloudCommon):
    class_name = "rviz/PointCloud2"
    message_types = ("sensor_msgs/PointCloud2",)
    defaults = {**PointCloudCommon.defaults, "Topic": "/points"}

    def points(self, message: Any) -> tuple[np.ndarray, dict[str, np.ndarray]] | str:
        points = cloud_array(message)
        names = points.dtype.names or ()
        if not {"x", "y", "z"} <= set(names):
            return "the cloud has no x, y, z fields"
        xyz = np.empty((len(points), 3), dtype=np.float32)  # float32 throughout: what GL draws
        for axis, name in enumerate("xyz"):
            xyz[:, axis] = points[name]
        return xyz, {name: points[name] for name in names}


def _arrow(scene: Scene, matrix: np.ndarray, length: float, color: Any) -> None:
    start, end = apply(matrix, [[0, 0, 0], [length, 0, 0]])
    scene.add("triangles", arrow_triangles(start, end, length * 0.1, length * 0.2, length * 0.3), color)


class Pose(Display):
    class_name = "rviz/Pose"
    message_types = ("geometry_msgs/PoseStamped",)
    defaults = {"Topic": "/pose", "Color": "255; 25; 0", "Alpha": 1, "Shaft Length": 1, "Shape": "Arrow"}

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        placed = self.placed(frames, self.message.header.frame_id)
        if placed is None:
            return
        matrix = placed @ pose_matrix(self.message.pose)
        if self.options.get("Shape") == "Axes":
            axes_lines(scene, matrix, self.number("Axes Length", 1.0))
        else:
            _arrow(scene, matrix, self.number("Shaft Length", 1.0) * 1.3, self.color())


class Odometry(Display):
    """Each message's pose as an arrow; the last `Keep` stay (rviz's odometry trail)."""
    class_name = "rviz/Odometry"
    message_types = ("nav_msgs/Odometry",)
    # rviz 1.14 keeps the arrow's look under "Shape"; older files (turtlebot's) have it flat
    defaults = {"Topic": "/odom", "Keep": 100, "Position Tolerance": 0.1, "Angle Tolerance": 0.1}
    SHAPE = {"Value": "Arrow", "Color": "255; 25; 0", "Alpha": 1, "Shaft Length": 1}

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.kept: list[Any] = []

    keeps_every_message = True

    def receive(self, messages: Any, now: float) -> None:
        keep = max(1, int(self.number("Keep", 100)))
        for message in messages:
            self.message = message
            self.version += 1
            if self.kept and not self._moved(self.kept[-1], message):
                continue
            self.kept = [*self.kept, message][-keep:]

    def _moved(self, before: Any, after: Any) -> bool:
        a, b = before.pose.pose, after.pose.pose
        distance = math.dist((a.position.x, a.position.y, a.position.z), (b.position.x, b.position.y, b.position.z))
        dot = abs(a.orientation.x * b.orientation.x + a.orientation.y * b.orientation.y
                  + a.orientation.z * b.orientation.z + a.orientation.w * b.orientation.w)
        angle = 2 * math.acos(min(1.0, dot))
        return (distance > self.number("Position Tolerance", 0.1) or angle > self.number("Angle Tolerance", 0.1)
                or before.header.frame_id != after.header.frame_id)

    def reset(self) -> None:
        super().reset()
        self.kept = []

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        shape = self.options.get("Shape")
        flat = {key: self.options[key] for key in ("Color", "Alpha", "Shaft Length") if key in self.options}
        look = {**self.SHAPE, **flat, **(shape if isinstance(shape, dict) else {})}
        r, g, b, _ = parse_color(look["Color"], (1.0, 25 / 255, 0.0, 1.0))
        try:
            alpha, length = float(look["Alpha"]), float(look["Shaft Length"])
        except (TypeError, ValueError):
            alpha, length = 1.0, 1.0
        for message in self.kept:
            placed = self.placed(frames, message.header.frame_id)
            if placed is not None:
                _arrow(scene, placed @ pose_matrix(message.pose.pose), length, (r, g, b, alpha))


class PoseArray(Display):
    class_name = "rviz/PoseArray"
    message_types = ("geometry_msgs/PoseArray",)
    defaults = {"Topic": "/particlecloud", "Color": "255; 25; 0", "Alpha": 1, "Arrow Length": 0.3}

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        placed = self.placed(frames, self.message.header.frame_id)
        if placed is None:
            return
        length = self.number("Arrow Length", 0.3)
        segments = []
        for pose in self.message.poses:  # rviz's flat arrows: a shaft and two head strokes
            m = placed @ pose_matrix(pose)
            tip, tail = apply(m, [[length, 0, 0], [0, 0, 0]])
            left, right = apply(m, [[length * 0.7, length * 0.15, 0], [length * 0.7, -length * 0.15, 0]])
            segments += [tail, tip, tip, left, tip, right]
        scene.add("lines", segments, self.color(), 1.5)


class PointStamped(Display):
    class_name = "rviz/PointStamped"
    message_types = ("geometry_msgs/PointStamped",)
    defaults = {"Topic": "/clicked_point", "Color": "204; 41; 204", "Alpha": 1, "Radius": 0.2}

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        placed = self.placed(frames, self.message.header.frame_id)
        if placed is None:
            return
        p = self.message.point
        radius = self.number("Radius", 0.2)
        center = apply(placed, [[p.x, p.y, p.z]])[0]
        scene.add("triangles", sphere_triangles((2 * radius,) * 3) + center, self.color())


class Path(Display):
    class_name = "rviz/Path"
    message_types = ("nav_msgs/Path",)
    defaults = {"Topic": "/path", "Color": "25; 255; 0", "Alpha": 1, "Line Width": 2}

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        placed = self.placed(frames, self.message.header.frame_id)
        if placed is None:
            return
        points = np.array([[s.pose.position.x, s.pose.position.y, s.pose.position.z] for s in self.message.poses])
        if len(points) >= 2:
            strip = apply(placed, points)
            scene.add("lines", np.repeat(strip, 2, axis=0)[1:-1], self.color(), self.number("Line Width", 2))


class Polygon(Display):
    class_name = "rviz/Polygon"
    message_types = ("geometry_msgs/PolygonStamped",)
    defaults = {"Topic": "/polygon", "Color": "25; 255; 0", "Alpha": 1}

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        placed = self.placed(frames, self.message.header.frame_id)
        if placed is None:
            return
        points = np.array([[p.x, p.y, p.z] for p in self.message.polygon.points])
        if len(points) >= 2:
            loop = apply(placed, np.vstack([points, points[:1]]))
            scene.add("lines", np.repeat(loop, 2, axis=0)[1:-1], self.color(), 2)


def map_palette() -> np.ndarray:
    """rviz's "map" scheme: 0 white-ish to 100 black, unknown (-1) grey-green."""
    palette = np.zeros((256, 4), dtype=np.uint8)
    values = np.arange(101)
    palette[:101, :3] = (255 - values * 255 // 100)[:, None]
    palette[:, 3] = 255
    palette[101:] = (0x70, 0x89, 0x86, 255)  # -1 as uint8 is 255
    return palette


def costmap_palette() -> np.ndarray:
    """rviz's "costmap" scheme: free transparent, 1..98 blue to red, 99 cyan, 100 purple."""
    palette = np.zeros((256, 4), dtype=np.uint8)
    values = np.arange(1, 99)
    palette[1:99] = np.column_stack([values * 255 // 98, np.zeros_like(values), 255 - values * 255 // 98,
                                     np.full_like(values, 255)])
    palette[99] = (0, 255, 255, 255)
    palette[100] = (255, 0, 255, 255)
    palette[101:] = (0x70, 0x89, 0x86, 64)
    return palette


class OccupancyGrid(Display):
    class_name = "rviz/Map"
    message_types = ("nav_msgs/OccupancyGrid",)
    defaults = {"Topic": "/map", "Alpha": 0.7, "Color Scheme": "map", "Draw Behind": False}

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._coloured: tuple[Any, str, float, np.ndarray] | None = None  # a map is coloured once, not each frame

    def _rgba(self, grid: Any) -> np.ndarray:
        scheme, alpha = str(self.options.get("Color Scheme")), self.number("Alpha", 0.7)
        if self._coloured is not None and self._coloured[:3] == (grid, scheme, alpha):
            return self._coloured[3]
        palette = costmap_palette() if scheme == "costmap" else map_palette()
        palette[:, 3] = (palette[:, 3] * alpha).astype(np.uint8)  # 256 entries, not 4 M cells
        cells = np.asarray(grid.data, dtype=np.int8).view(np.uint8).reshape(grid.info.height, grid.info.width)
        # each cell's 4 bytes gathered as one 32-bit word
        rgba = palette.view(np.uint32)[:, 0][cells].view(np.uint8).reshape(grid.info.height, grid.info.width, 4)
        self._coloured = (grid, scheme, alpha, rgba)
        return rgba

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        grid = self.message
        placed = self.placed(frames, grid.header.frame_id)
        if placed is None:
            return
        width, height, resolution = grid.info.width, grid.info.height, grid.info.resolution
        if width * height == 0 or len(grid.data) != width * height:
            self.status = Status(WARN, f"the map's data has {len(grid.data)} cells, not {width}x{height}")
            return
        rgba = self._rgba(grid)
        origin = placed @ pose_matrix(grid.info.origin)
        corners = apply(origin, [[0, 0, 0], [width * resolution, 0, 0], [width * resolution, height * resolution, 0],
                                 [0, height * resolution, 0]])
        scene.texture(corners, rgba)
