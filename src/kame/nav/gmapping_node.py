"""slam_gmapping, the node: builds a map from a robot's laser and odometry (kame.nav.slam's filter).

    rosrun gmapping slam_gmapping [scan:=...]

As gmapping's: reads `scan` (sensor_msgs/LaserScan) and the odometry from tf (~odom_frame ->
~base_frame at each scan's stamp, and ~base_frame -> the scan's frame); publishes `map`
(nav_msgs/OccupancyGrid) and `map_metadata` (nav_msgs/MapMetaData), latched, after the first
scan and then at most every ~map_update_interval seconds, `~entropy` (std_msgs/Float64, of the
particles' weights) after every processed scan, and the transform ~map_frame -> ~odom_frame every
~transform_publish_period seconds (stamped that far ahead); serves `dynamic_map`
(nav_msgs/GetMap). The filter's parameters are gmapping's, with its defaults (maxRange: the
scan's range_max less 1 cm; maxUrange: maxRange); ~throttle_scans uses every n-th scan.
A scan whose angles or range limits are NaN or inf (kame.nav.inputs) is left out with a warning,
at most one each 10 s: a NaN angle would be drawn into the map for good.
"""

from __future__ import annotations

import math
import sys
import threading
from collections.abc import Sequence
from typing import Any

import numpy as np

from kame.client import clock, core, process, services, timer, topics
from kame.client import log as _log
from kame.nav import inputs
from kame.nav.amcl_node import compose, inverse, yaw_of
from kame.nav.slam import Gmapping, GmappingParams, MapView
from kame.tf import errors as tf_errors
from kame.tf.transformations import quaternion_from_euler
from kame.tf_ros.buffer import Buffer
from kame.tf_ros.node_io import TransformBroadcaster, TransformListener

_FIELDS = GmappingParams.__dataclass_fields__
_SET_FROM_THE_SCAN = ("maxRange", "maxUrange")  # unset: from the first scan, as slam_gmapping


def _param(name: str, default: Any) -> Any:
    return process.get_param("~" + name, default)


def filter_params(range_max: float) -> GmappingParams:
    values: dict[str, Any] = {}
    for name, spec in _FIELDS.items():
        kind = int if spec.type in ("int", int) else float
        value = _param(name, None)
        if value is not None:
            values[name] = kind(value)
    if "maxRange" not in values:
        values["maxRange"] = range_max - 0.01
    values.setdefault("maxUrange", values["maxRange"])
    return GmappingParams(**values)


class SlamGmapping:
    def __init__(self) -> None:
        self.base_frame = str(_param("base_frame", "base_link"))
        self.map_frame = str(_param("map_frame", "map"))
        self.odom_frame = str(_param("odom_frame", "odom"))
        self.map_update_interval = float(_param("map_update_interval", 5.0))
        self.throttle_scans = max(1, int(_param("throttle_scans", 1)))
        self.transform_publish_period = float(_param("transform_publish_period", 0.05))
        self.seed = int(_param("seed", 0))
        self.lock = threading.Lock()
        self.slam: Gmapping | None = None
        self.scans = 0
        self.map_to_odom: tuple[float, float, float] = (0.0, 0.0, 0.0)
        self.last_map_update: float | None = None
        self.map_msg: Any = None
        self.last_transform_stamp: Any = None
        node = core.get_node()
        assert node is not None
        self.buffer = Buffer(warn=lambda text: _log.emit(_log.WARN, text, ()))
        self.listener = TransformListener(node, self.buffer, now=lambda: clock.get_rostime().to_nsec())
        self.broadcaster = TransformBroadcaster(node)
        from nav_msgs.msg import MapMetaData, OccupancyGrid
        from std_msgs.msg import Float64
        self.map_pub = topics.Publisher("map", OccupancyGrid, queue_size=1, latch=True)
        self.metadata_pub = topics.Publisher("map_metadata", MapMetaData, queue_size=1, latch=True)
        self.entropy_pub = topics.Publisher("~entropy", Float64, queue_size=1)

    def _pose_of(self, target: str, source: str, stamp: Any) -> tuple[float, float, float]:
        found = self.buffer.lookup_transform(target, source, stamp, clock.Duration(0.2))
        t, q = found.transform.translation, found.transform.rotation
        return t.x, t.y, yaw_of(q)

    def on_scan(self, scan: Any) -> None:
        self.scans += 1
        if self.scans % self.throttle_scans:
            return
        problem = inputs.scan_problem(scan, finite_range=True)
        if problem is not None:
            _log.emit_throttle(10.0, _log.WARN, "Ignoring a scan in frame %s: %s", (scan.header.frame_id, problem))
            return
        try:
            odom = self._pose_of(self.odom_frame, self.base_frame, scan.header.stamp)
            mount = self._pose_of(self.base_frame, scan.header.frame_id, scan.header.stamp)
        except tf_errors.TransformException as exc:
            _log.emit_throttle(5.0, _log.WARN, "Failed to compute odom pose, skipping scan (%s)", (exc,))
            return
        ranges = np.asarray(scan.ranges, dtype=float)
        ranges = np.where(ranges < scan.range_min, 0.0, ranges)  # too near: no return
        angles = scan.angle_min + scan.angle_increment * np.arange(len(ranges))
        laser = compose(odom, mount)  # the filter follows the laser, the map frame the base
        with self.lock:
            if self.slam is None:
                params = filter_params(float(scan.range_max))
                _log.emit(_log.INFO, "Laser is mounted upwards.", ())
                self.slam = Gmapping(params, seed=self.seed)
                _log.emit(_log.INFO, "Initialization complete", ())
            slam = self.slam
            if not slam.add_scan(laser, ranges, angles, float(scan.range_max), scan.header.stamp.to_sec()):
                return
            base_in_map = compose(slam.best_pose(), inverse(mount))
            self.map_to_odom = compose(base_in_map, inverse(odom))
            entropy = slam.entropy()
            now = scan.header.stamp.to_sec()
            due = self.last_map_update is None or now - self.last_map_update > self.map_update_interval
            view = slam.occupancy() if due else None
        from std_msgs.msg import Float64
        self.entropy_pub.publish(Float64(entropy))
        if view is not None:
            self.last_map_update = now
            self._publish_map(view, scan.header.stamp)

    def _publish_map(self, view: MapView, stamp: Any) -> None:
        from nav_msgs.msg import OccupancyGrid
        grid = OccupancyGrid()
        grid.header.stamp, grid.header.frame_id = stamp, self.map_frame
        info = grid.info
        info.map_load_time = stamp
        info.resolution = view.resolution
        info.height, info.width = view.cells.shape
        info.origin.position.x, info.origin.position.y = view.origin
        info.origin.orientation.w = 1.0
        grid.data = view.cells.reshape(-1).copy()  # a copy: the filter keeps updating its cells
        with self.lock:
            self.map_msg = grid
        self.map_pub.publish(grid)
        self.metadata_pub.publish(info)

    def dynamic_map(self, _request: Any) -> Any:
        from nav_msgs.srv import GetMapResponse
        with self.lock:
            grid = self.map_msg
        if grid is None:
            raise ValueError("no map yet")  # gmapping's service returns false until the first map
        return GetMapResponse(grid)

    def publish_transform(self, _event: Any = None) -> None:
        from geometry_msgs.msg import TransformStamped
        with self.lock:
            x, y, theta = self.map_to_odom
        stamp = clock.Time.from_sec(clock.get_rostime().to_sec() + self.transform_publish_period)
        if stamp == self.last_transform_stamp:
            return  # simulated time stood still since the last: tf would take it for repeated data
        self.last_transform_stamp = stamp
        t = TransformStamped()
        t.header.stamp = stamp
        t.header.frame_id, t.child_frame_id = self.map_frame, self.odom_frame
        t.transform.translation.x, t.transform.translation.y = x, y
        q = quaternion_from_euler(0.0, 0.0, theta)
        t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z, t.transform.rotation.w = \
            (float(v) for v in q)
        self.broadcaster.send_transform(t)


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    _log.use_roscpp_console()
    process.init_node("slam_gmapping", argv=argv)
    from nav_msgs.srv import GetMap
    from sensor_msgs.msg import LaserScan

    try:
        filter_params(10.0)  # bad parameters are an error line now, not at the first scan
    except (TypeError, ValueError) as exc:
        _log.emit(_log.ERROR, "slam_gmapping: bad parameter: %s", (exc,))
        return 1
    node = SlamGmapping()
    # the newest scan only: one that waited while the filter worked is stale (and its odometry
    # may have left tf's cache); the filter integrates the motion between the scans it takes
    topics.Subscriber("scan", LaserScan, node.on_scan, queue_size=1)
    services.Service("dynamic_map", GetMap, node.dynamic_map)
    publisher = None
    if node.transform_publish_period > 0 and math.isfinite(node.transform_publish_period):
        publisher = timer.Timer(clock.Duration.from_sec(node.transform_publish_period), node.publish_transform)
    process.spin()
    if publisher is not None:
        publisher.shutdown()
        publisher.join()
    return 0
