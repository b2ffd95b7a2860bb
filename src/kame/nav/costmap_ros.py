"""costmap_2d's Costmap2DROS for kame's move_base: one named costmap (global_costmap or
local_costmap) kept up to date from the laser and published for rviz.

    ~<name>/costmap (nav_msgs/OccupancyGrid, at publish_frequency; latched)
    ~<name>/footprint (geometry_msgs/PolygonStamped, the robot's footprint where it stands)

A static costmap is the map's size (the map comes from map_server's `map`); a rolling one
(rolling_window) is width x height metres kept centred on the robot in its global_frame. The
obstacle layer takes the newest scan of each LaserScan observation source at update_frequency
(observation_persistence 0, as the TurtleBot's), clearing along its rays and marking its hits.
"""

from __future__ import annotations

import math
import threading
from typing import Any

import numpy as np

from kame.client import clock, topics
from kame.client import log as _log
from kame.nav import inputs
from kame.nav.amcl_node import yaw_of
from kame.nav.config import CostmapConfig
from kame.nav.costmap import Costmap
from kame.tf import errors as tf_errors
from kame.tf_ros.buffer import Buffer

# costmap_2d's cost_translation_table: free 0, inscribed 99, lethal 100, unknown -1, the rest 1..98
_TRANSLATION = np.array([0] + [1 + (97 * (i - 1)) // 251 for i in range(1, 253)] + [99, 100, -1], dtype=np.int8)


def circle_footprint(radius: float) -> tuple[tuple[float, float], ...]:
    """costmap_2d's polygon for a round robot: 16 points on the circle."""
    return tuple((radius * math.cos(a), radius * math.sin(a)) for a in np.arange(16) * (2 * math.pi / 16))


class CostmapROS:
    def __init__(self, config: CostmapConfig, buffer: Buffer) -> None:
        from geometry_msgs.msg import PolygonStamped
        from nav_msgs.msg import OccupancyGrid
        self.config = config
        self.buffer = buffer
        self.lock = threading.Lock()  # the costmap is read by the planners, written by the updates
        self.costmap: Costmap | None = None
        self.footprint = config.footprint or circle_footprint(config.robot_radius)
        self.applied: dict[str, Any] = {}  # the stamp of each source's scan already in the costmap
        self.next_update = 0.0
        self.next_publish = 0.0
        self.grid_pub = topics.Publisher(f"~{config.name}/costmap", OccupancyGrid, queue_size=1, latch=True)
        self.footprint_pub = topics.Publisher(f"~{config.name}/footprint", PolygonStamped, queue_size=1)
        if config.rolling_window:
            columns = max(1, round(config.width / config.resolution))
            rows = max(1, round(config.height / config.resolution))
            self.costmap = Costmap(np.zeros((rows, columns), np.int16), config.resolution,
                                   (-config.width / 2, -config.height / 2), config.layers)

    def on_map(self, msg: Any) -> None:
        if self.config.rolling_window:
            return
        info = msg.info
        data = msg.data
        problem = inputs.map_problem(info, len(data))
        if problem is not None:
            _log.emit(_log.ERROR, "%s: ignoring the map: %s", (self.config.name, problem))
            return
        cells = np.frombuffer(data, dtype=np.int8) if isinstance(data, bytes) else np.asarray(data, np.int16)
        costmap = Costmap(cells.reshape(info.height, info.width), info.resolution,
                          (info.origin.position.x, info.origin.position.y), self.config.layers)
        with self.lock:
            self.costmap = costmap
        self.next_publish = 0.0

    def robot_pose(self, timeout: float = 0.5) -> tuple[float, float, float] | None:
        try:
            found = self.buffer.lookup_transform(self.config.global_frame, self.config.robot_base_frame, 0,
                                                 clock.Duration(timeout))
        except tf_errors.TransformException as exc:
            _log.emit_throttle(5.0, _log.WARN, "Unable to get the robot's pose in %s: %s",
                               (self.config.global_frame, exc))
            return None
        return found.transform.translation.x, found.transform.translation.y, yaw_of(found.transform.rotation)

    # ---------------------------------------------------------------- updates

    def update(self, now: float, scans: dict[str, Any]) -> None:
        """Once every 1 / update_frequency: follow the robot (rolling), add the newest scans,
        publish the footprint; the grid once every 1 / publish_frequency."""
        if now < self.next_update or self.costmap is None:
            return
        frequency = self.config.update_frequency
        self.next_update = now + (1.0 / frequency if frequency > 0 else 0.0)
        pose = self.robot_pose(0.1)
        if pose is not None and self.config.rolling_window:
            with self.lock:
                self.costmap.recentre(pose[:2])
        for source in self.config.sources:
            scan = scans.get(source.topic)
            if scan is None or source.data_type != "LaserScan" or self.applied.get(source.name) == scan.header.stamp:
                continue
            self.applied[source.name] = scan.header.stamp
            observation = self._observe(scan)
            if observation is not None:
                with self.lock:
                    self.costmap.update_from_scan(observation[0], observation[1], source.marking, source.clearing)
        if pose is not None:
            self._publish_footprint(pose)
        if self.config.publish_frequency > 0 and now >= self.next_publish:
            self.next_publish = now + 1.0 / self.config.publish_frequency
            self.publish()

    def _observe(self, scan: Any) -> tuple[tuple[float, float], np.ndarray] | None:
        try:
            found = self.buffer.lookup_transform(self.config.global_frame, scan.header.frame_id, scan.header.stamp,
                                                 clock.Duration(0.2))
        except tf_errors.TransformException:
            return None
        x, y = found.transform.translation.x, found.transform.translation.y
        yaw = yaw_of(found.transform.rotation)
        ranges = np.asarray(scan.ranges, dtype=float)
        angles = yaw + scan.angle_min + scan.angle_increment * np.arange(len(ranges))
        seen = np.isfinite(ranges) & (ranges >= scan.range_min) & (ranges < scan.range_max)
        points = np.column_stack((x + ranges[seen] * np.cos(angles[seen]), y + ranges[seen] * np.sin(angles[seen])))
        return (x, y), points

    def clear(self, around: tuple[float, float] | None = None, keep_size: float = 0.0) -> None:
        with self.lock:
            if self.costmap is not None:
                self.costmap.clear_obstacles(around, keep_size)

    # ---------------------------------------------------------------- outputs

    def publish(self) -> None:
        from nav_msgs.msg import OccupancyGrid
        with self.lock:
            if self.costmap is None:
                return
            costs = self.costmap.costs.copy()
            origin, resolution = self.costmap.origin, self.costmap.resolution
        grid = OccupancyGrid()
        grid.header.frame_id = self.config.global_frame
        grid.header.stamp = clock.get_rostime()
        grid.info.resolution = resolution
        grid.info.height, grid.info.width = costs.shape
        grid.info.origin.position.x, grid.info.origin.position.y = origin
        grid.info.origin.orientation.w = 1.0
        # int8[] fields take numpy arrays whole; a list of every cell cost more than the publish itself.
        grid.data = _TRANSLATION[costs].reshape(-1)
        self.grid_pub.publish(grid)

    def _publish_footprint(self, pose: tuple[float, float, float]) -> None:
        from geometry_msgs.msg import Point32, PolygonStamped
        msg = PolygonStamped()
        msg.header.frame_id = self.config.global_frame
        msg.header.stamp = clock.get_rostime()
        c, s = math.cos(pose[2]), math.sin(pose[2])
        for fx, fy in self.footprint:
            msg.polygon.points.append(Point32(x=pose[0] + c * fx - s * fy, y=pose[1] + s * fx + c * fy, z=0.0))
        self.footprint_pub.publish(msg)
