"""The ray-sensor plugins: laser (also gpu_laser and ray_sensor: sensor_msgs/LaserScan),
block_laser (sensor_msgs/PointCloud of every ray) and range (sensor_msgs/Range, sonar or
infrared: the nearest of the sensor's rays), on the scans kame.gazebo's World casts for the
sensor's <ray> (+inf where a ray hits nothing within its range, the SDF <noise> already added);
range's and block_laser's own <gaussianNoise> on top, as those plugins add it.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from kame.gazebo_ros.conversions import stamp
from kame.gazebo_ros.plugins.base import Every, GazeboPlugin, PluginContext
from kame.gazebo_ros.plugins.parameters import PluginParameterError

LASER_MISSING = "GazeboRosLaser Plugin missing <{tag}>, defaults to {default}"
RANGE_MISSING = "Range plugin missing <{tag}>, defaults to {default}"
BLOCK_MISSING = "Block laser plugin missing <{tag}>, defaults to {default}"


class _RaySensorPlugin(GazeboPlugin):
    """A plugin on a ray sensor: its sensor, its rate, its noise."""

    def __init__(self, context: PluginContext, kind: str) -> None:
        super().__init__(context)
        sensor = context.sensor()
        if sensor is None or sensor.type not in ("ray", "gpu_ray", "sonar"):
            raise PluginParameterError(f"{kind} plugin must sit in a ray sensor (<sensor type=\"ray\">), "
                                       f"not in {sensor.type if sensor else 'a model'}")
        self.sensor = sensor
        self.sensor_info = context.sensor_info()
        self.rng = context.world.rng

    def _scan(self) -> Any:
        """The sensor's scan now: kame.gazebo's RayScan (angles, config, ranges rows x columns)."""
        return self.context.world.ray_scan(self.sensor_info)

    def _noisy(self, ranges: np.ndarray, stddev: float) -> np.ndarray:
        if stddev <= 0:
            return ranges
        noisy: np.ndarray = ranges + self.rng.normal(0.0, stddev, ranges.shape)
        return noisy


class Laser(_RaySensorPlugin):
    """libgazebo_ros_laser.so (and gpu_laser, ray_sensor): the middle row of rays as a LaserScan."""

    def __init__(self, context: PluginContext) -> None:
        from sensor_msgs.msg import LaserScan

        super().__init__(context, "GazeboRosLaser")
        p = context.parameters("GazeboRosLaser", LASER_MISSING)
        namespace = context.namespace(p)
        self.frame = p.text("frameName", "/world")
        topic = p.text("topicName", "/world")
        rate = p.number("updateRate", self.sensor.update_rate, quiet=True)
        context.report(p)
        self.rate = Every(rate)
        self.scan = self.own(context.publisher(namespace, topic, LaserScan))
        context.info(f"Starting Laser Plugin (ns = {namespace})")

    def update(self, now: float) -> None:
        if not self.rate.due(now) or (not self.sensor.always_on and self.scan.get_num_connections() == 0):
            return
        from sensor_msgs.msg import LaserScan

        scan = self._scan()
        row = scan.ranges[scan.ranges.shape[0] // 2]  # the middle row, as a planar laser's one
        angles = scan.horizontal_angles
        msg = LaserScan()
        msg.header.stamp = stamp(now)
        msg.header.frame_id = self.frame.lstrip("/")
        msg.angle_min, msg.angle_max = float(angles[0]), float(angles[-1])
        msg.angle_increment = float(angles[1] - angles[0]) if len(angles) > 1 else 0.0
        msg.time_increment = 0.0
        msg.scan_time = self.rate.period
        msg.range_min, msg.range_max = scan.config.range_min, scan.config.range_max
        msg.ranges = row.astype(np.float32)
        msg.intensities = np.zeros(len(row), dtype=np.float32)
        self.scan.publish(msg)


class Range(_RaySensorPlugin):
    """libgazebo_ros_range.so: the nearest ray as a Range (sonar or infrared)."""

    def __init__(self, context: PluginContext) -> None:
        from sensor_msgs.msg import Range as RangeMsg

        super().__init__(context, "Range")
        p = context.parameters("Range", RANGE_MISSING)
        namespace = context.namespace(p)
        topic = p.text("topicName", "/range")
        self.frame = p.text("frameName", "/world")
        radiation = p.text("radiation", "ultrasound").lower()
        if radiation not in ("ultrasound", "infrared"):
            raise PluginParameterError(f"Range plugin: <radiation> must be ultrasound or infrared, not {radiation!r}")
        self.radiation = RangeMsg.INFRARED if radiation == "infrared" else RangeMsg.ULTRASOUND
        self.fov = p.number("fov", 0.05)
        self.noise = p.number("gaussianNoise", 0.0)
        rate = p.number("updateRate", self.sensor.update_rate)
        context.report(p)
        self.rate = Every(rate)
        self.range = self.own(context.publisher(namespace, topic, RangeMsg))

    def update(self, now: float) -> None:
        if not self.rate.due(now) or (not self.sensor.always_on and self.range.get_num_connections() == 0):
            return
        from sensor_msgs.msg import Range as RangeMsg

        scan = self._scan()
        config = scan.config
        nearest = float(np.min(scan.ranges)) if scan.ranges.size else math.inf
        if nearest < config.range_max:  # as gazebo_ros_range: noise only on a hit, never past the maximum
            nearest = min(float(self._noisy(np.array([nearest]), self.noise)[0]), config.range_max)
        msg = RangeMsg()
        msg.header.stamp = stamp(now)
        msg.header.frame_id = self.frame.lstrip("/")
        msg.radiation_type = self.radiation
        msg.field_of_view = self.fov
        msg.min_range, msg.max_range = config.range_min, config.range_max
        # nothing in range: gazebo_ros_range keeps its initial value, the largest float32
        msg.range = nearest if math.isfinite(nearest) else float(np.finfo(np.float32).max)
        self.range.publish(msg)


class BlockLaser(_RaySensorPlugin):
    """libgazebo_ros_block_laser.so: every ray's hit as a point (sensor_msgs/PointCloud)."""

    def __init__(self, context: PluginContext) -> None:
        from sensor_msgs.msg import PointCloud

        super().__init__(context, "Block laser")
        p = context.parameters("Block laser", BLOCK_MISSING)
        namespace = context.namespace(p)
        topic = p.text("topicName", "/world")
        self.frame = p.text("frameName", "/world")
        self.noise = p.number("gaussianNoise", 0.0)
        rate = p.number("updateRate", self.sensor.update_rate, quiet=True)
        context.report(p)
        self.rate = Every(rate)
        self.cloud = self.own(context.publisher(namespace, topic, PointCloud))

    def update(self, now: float) -> None:
        if not self.rate.due(now) or (not self.sensor.always_on and self.cloud.get_num_connections() == 0):
            return
        from geometry_msgs.msg import Point32
        from sensor_msgs.msg import ChannelFloat32, PointCloud

        scan = self._scan()
        range_max = scan.config.range_max
        ranges = self._noisy(scan.ranges, self.noise)
        yaws = np.asarray(scan.horizontal_angles)[np.newaxis, :]
        pitches = np.asarray(scan.vertical_angles)[:, np.newaxis]
        hit = np.isfinite(ranges) & (ranges <= range_max)
        # as gazebo_ros_block_laser: a ray that hits nothing is a point at the maximum range
        ranges = np.where(hit, ranges, range_max)
        x = ranges * np.cos(pitches) * np.cos(yaws)
        y = ranges * np.cos(pitches) * np.sin(yaws)
        z = ranges * np.sin(pitches) * np.ones_like(yaws)
        msg = PointCloud()
        msg.header.stamp = stamp(now)
        msg.header.frame_id = self.frame.lstrip("/")
        msg.points = [Point32(float(a), float(b), float(c)) for a, b, c in zip(x.ravel(), y.ravel(), z.ravel(),
                                                                                strict=True)]
        msg.channels = [ChannelFloat32("intensity", [1.0 if h else 0.0 for h in hit.ravel()])]
        self.cloud.publish(msg)
