"""Sensors computed from the world's state, as Gazebo's sensors compute them: ray (laser) scans,
range (sonar, IR), IMU, contacts (bumper); cameras are in kame.gazebo.camera.

- Rays are cast by MuJoCo (mj_multiRay) against collision shapes, from the sensor's origin,
  ignoring the sensor's own link and the links welded to it by fixed joints (Gazebo lumps those
  into one link, whose collisions its rays skip: a URDF's cliff sensor inside the base sees the
  floor, not the base). A ray's reading starts at the range's min (nearer hits are not
  seen, as Gazebo's rays start there); beyond max (or no hit) it is +inf. `samples` x
  `resolution` rays are cast over [min_angle, max_angle], horizontal and vertical. Gaussian
  noise (mean, stddev) is added to finite readings, then clipped to [min, max]; none without a
  <noise> element. The range's <resolution> is carried in the configuration, not applied (Gazebo
  does not round ranges to it either).
- A range sensor is the nearest of its rays: a ray sensor's own samples (gazebo_ros_range over
  a <ray>), or for <sonar> a cone of rays whose radius at max range is the sonar's radius.
- An IMU reads MuJoCo's gyro and accelerometer at its site (the acceleration includes gravity's
  reaction, +9.8 upward at rest, as Gazebo's) and the site's orientation; Gaussian noise per
  SDF's <angular_velocity>/<linear_acceleration> <x>/<y>/<z> <noise>, or SDF 1.4's <noise><rate>/<accel>.
- Contacts of a link: each MuJoCo contact touching one of its collisions: both collisions' names
  (model::link::collision), the position, the normal (from the link's collision outward), depth
  and the contact force on the link, in the world frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from kame.gazebo.assembly import COLLISION_GROUP
from kame.gazebo.engine import mujoco
from kame.gazebo.errors import GazeboError
from kame.gazebo.poses import Pose, Quaternion, Vector3
from kame.gazebo.xmltree import Element

_COLLISIONS = np.zeros(6, dtype=np.uint8)
_COLLISIONS[COLLISION_GROUP] = 1
MAX_RECASTS = 8  # a ray passes at most this many welded links' collisions (and the range's min)


@dataclass(frozen=True)
class RayAxis:
    samples: int = 1
    resolution: float = 1.0
    min_angle: float = 0.0
    max_angle: float = 0.0

    def angles(self) -> np.ndarray:
        count = max(1, round(self.samples * self.resolution))
        return np.linspace(self.min_angle, self.max_angle, count) if count > 1 else np.array([self.min_angle])


@dataclass(frozen=True)
class RayConfig:
    horizontal: RayAxis
    vertical: RayAxis
    range_min: float
    range_max: float
    range_resolution: float
    noise_mean: float = 0.0
    noise_stddev: float = 0.0

    @cached_property
    def horizontal_angles(self) -> np.ndarray:
        return self.horizontal.angles()

    @cached_property
    def vertical_angles(self) -> np.ndarray:
        return self.vertical.angles()

    @cached_property
    def directions(self) -> np.ndarray:
        """Every ray's unit direction in the sensor's frame, vertical-major (computed once a sensor)."""
        return ray_directions(self.horizontal_angles, self.vertical_angles)

    @staticmethod
    def of(sensor: Element) -> RayConfig:
        ray = sensor.child("ray") or sensor.child("lidar")
        if ray is None:
            raise GazeboError(f"{sensor.where()}: a ray sensor needs a <ray>")
        scan = ray.child("scan")
        horizontal = _axis(scan.child("horizontal") if scan is not None else None)
        vertical = _axis(scan.child("vertical") if scan is not None else None)
        ranges = ray.child("range")
        if ranges is None:
            raise GazeboError(f"{ray.where()}: a ray sensor needs a <range> with <min> and <max>")
        config = RayConfig(horizontal, vertical, ranges.number("min", 0.0), ranges.number("max", 1.0),
                           ranges.number("resolution", 0.0), *_gaussian(ray.child("noise")))
        if not (0 <= config.range_min < config.range_max) or not math.isfinite(config.range_max):
            raise GazeboError(f"{ranges.where()}: needs 0 <= min < max, finite")
        if horizontal.samples * vertical.samples * max(horizontal.resolution, 1) * max(vertical.resolution, 1) > 1e6:
            raise GazeboError(f"{ray.where()}: more than a million rays a scan")
        return config


def _axis(element: Element | None) -> RayAxis:
    if element is None:
        return RayAxis()
    axis = RayAxis(element.integer("samples", 1), element.number("resolution", 1.0),
                   element.number("min_angle", 0.0), element.number("max_angle", 0.0))
    if axis.samples < 1 or not axis.resolution > 0 or axis.min_angle > axis.max_angle:
        raise GazeboError(f"{element.where()}: needs samples >= 1, resolution > 0 and min_angle <= max_angle")
    return axis


def _gaussian(noise: Element | None) -> tuple[float, float]:
    if noise is None or (noise.child_text("type") or noise.attrs.get("type", "gaussian")) not in (
            "gaussian", "gaussian_quantized"):
        return 0.0, 0.0
    return noise.number("mean", 0.0), noise.number("stddev", 0.0)


@dataclass(frozen=True)
class RayScan:
    ranges: np.ndarray  # vertical x horizontal, metres; +inf where nothing is within range
    config: RayConfig
    horizontal_angles: np.ndarray
    vertical_angles: np.ndarray


def cast(model: mujoco.MjModel, data: mujoco.MjData, origin: Pose, body: int, directions: np.ndarray,
         range_min: float, range_max: float) -> np.ndarray:
    """Distances along unit `directions` (N x 3, in the origin's frame), from range_min out to range_max."""
    world_directions = directions @ origin.rotation().T
    start = np.asarray(origin.position)
    count = len(world_directions)
    found = np.empty(count)
    geoms = np.empty(count, dtype=np.int32)
    mujoco.mj_multiRay(model, data, start, world_directions.ravel().copy(), _COLLISIONS, 1, body, geoms, found,
                       None, count, range_max)
    weld = model.body_weldid[body]  # 0 when the link is fixed to the world: then only its own body is skipped
    welded = (model.body_weldid[model.geom_bodyid[geoms]] == weld) & (weld != 0)
    geom = np.empty(1, dtype=np.int32)
    for i in np.flatnonzero((found >= 0) & ((found < range_min) | welded)):  # seen past: cast again beyond
        direction = world_directions[i]
        begin, distance, hit_body = 0.0, float(found[i]), int(model.geom_bodyid[geoms[i]])
        for _ in range(MAX_RECASTS):
            at = begin + distance
            if distance < 0 or (at >= range_min and (weld == 0 or model.body_weldid[hit_body] != weld)):
                break
            # nearer than the range's min: from there; a welded link's collision: on past it
            begin, skipped = (range_min, body) if at < range_min else (at, hit_body)
            distance = mujoco.mj_ray(model, data, start + direction * begin, direction, _COLLISIONS, 1, skipped, geom)
            hit_body = int(model.geom_bodyid[geom[0]])
        found[i] = begin + distance if distance >= 0 else -1.0
    ranges = np.where(found < 0, np.inf, found)
    ranges[ranges > range_max] = np.inf
    return ranges


def ray_directions(horizontal: np.ndarray, vertical: np.ndarray) -> np.ndarray:
    v, h = np.meshgrid(vertical, horizontal, indexing="ij")
    return np.stack((np.cos(v) * np.cos(h), np.cos(v) * np.sin(h), np.sin(v)), axis=-1).reshape(-1, 3)


def ray_scan(model: mujoco.MjModel, data: mujoco.MjData, origin: Pose, body: int, config: RayConfig,
             rng: np.random.Generator) -> RayScan:
    horizontal, vertical = config.horizontal_angles, config.vertical_angles
    ranges = cast(model, data, origin, body, config.directions, config.range_min, config.range_max)
    if config.noise_stddev > 0 or config.noise_mean != 0:
        finite = np.isfinite(ranges)
        noisy = ranges[finite] + rng.normal(config.noise_mean, config.noise_stddev, int(finite.sum()))
        ranges[finite] = np.clip(noisy, config.range_min, config.range_max)
    return RayScan(ranges.reshape(len(vertical), len(horizontal)), config, horizontal, vertical)


@dataclass(frozen=True)
class RangeReading:
    range: float  # metres; +inf when nothing is within max
    min_range: float
    max_range: float
    field_of_view: float  # radians


def sonar_range(model: mujoco.MjModel, data: mujoco.MjData, origin: Pose, body: int, sonar: Element,
                rng: np.random.Generator) -> RangeReading:
    low, high, radius = sonar.number("min", 0.0), sonar.number("max", 1.0), sonar.number("radius", 0.5)
    if not (0 <= low < high) or radius < 0:
        raise GazeboError(f"{sonar.where()}: needs 0 <= min < max and radius >= 0")
    half = math.atan2(radius, high)
    angles = np.linspace(-half, half, 5)
    ranges = cast(model, data, origin, body, ray_directions(angles, angles), low, high)
    return RangeReading(float(ranges.min()), low, high, 2 * half)


def ray_range(scan: RayScan) -> RangeReading:
    config = scan.config
    span = max(config.horizontal.max_angle - config.horizontal.min_angle,
               config.vertical.max_angle - config.vertical.min_angle)
    return RangeReading(float(scan.ranges.min()), config.range_min, config.range_max, span)


@dataclass(frozen=True)
class ImuReading:
    orientation: Quaternion  # x, y, z, w: the IMU's frame in the world
    angular_velocity: Vector3  # rad/s in the IMU's frame
    linear_acceleration: Vector3  # m/s^2 in the IMU's frame, gravity's reaction included


def imu_reading(model: mujoco.MjModel, data: mujoco.MjData, name: str, sensor: Element,
                rng: np.random.Generator) -> ImuReading:
    values = {}
    for suffix in ("gyro", "accelerometer", "orientation"):
        found = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SENSOR, f"{name}::{suffix}")
        if found < 0:
            raise GazeboError(f"no IMU sensor named {name!r}")
        start, width = model.sensor_adr[found], model.sensor_dim[found]
        values[suffix] = np.array(data.sensordata[start:start + width])
    imu = sensor.child("imu")
    gyro_noise, accel_noise = _imu_noise(imu, "angular_velocity", "rate"), _imu_noise(imu, "linear_acceleration",
                                                                                       "accel")
    gyro = values["gyro"] + [rng.normal(m, s) if s > 0 or m else 0.0 for m, s in gyro_noise]
    accel = values["accelerometer"] + [rng.normal(m, s) if s > 0 or m else 0.0 for m, s in accel_noise]
    w, x, y, z = (float(v) for v in values["orientation"])
    return ImuReading((x, y, z, w), (float(gyro[0]), float(gyro[1]), float(gyro[2])),
                      (float(accel[0]), float(accel[1]), float(accel[2])))


def _imu_noise(imu: Element | None, tag: str, old_tag: str) -> list[tuple[float, float]]:
    """(mean, stddev) for x, y, z: SDF 1.5's <tag><x><noise>, or SDF 1.4's <noise><old_tag>."""
    if imu is None:
        return [(0.0, 0.0)] * 3
    per_axis = imu.child(tag)
    if per_axis is not None:
        axes = [per_axis.child(axis) for axis in "xyz"]
        return [_gaussian(a.child("noise")) if a is not None else (0.0, 0.0) for a in axes]
    noise = imu.child("noise")
    old = noise.child(old_tag) if noise is not None and (noise.child_text("type") or "gaussian") == "gaussian" else None
    if old is None:
        return [(0.0, 0.0)] * 3
    return [(old.number("mean", 0.0), old.number("stddev", 0.0))] * 3


@dataclass(frozen=True)
class Contact:
    collision1: str  # the link's collision: model::link::collision
    collision2: str  # what it touches
    position: Vector3
    normal: Vector3  # from collision1 outward, world frame
    depth: float  # metres of overlap
    force: Vector3  # on collision1's link, world frame


def contacts(model: mujoco.MjModel, data: mujoco.MjData, body: int) -> list[Contact]:
    found = []
    wrench = np.zeros(6)
    for index in range(data.ncon):
        contact = data.contact[index]
        bodies = (model.geom_bodyid[contact.geom1], model.geom_bodyid[contact.geom2])
        if body not in bodies:
            continue
        mine, other = (contact.geom1, contact.geom2) if bodies[0] == body else (contact.geom2, contact.geom1)
        sign = -1.0 if bodies[0] == body else 1.0  # MuJoCo's normal points from geom1 to geom2
        mujoco.mj_contactForce(model, data, index, wrench)
        frame = contact.frame.reshape(3, 3)
        on_geom2 = frame.T @ wrench[:3]  # the contact frame's force is what geom2 feels, along the normal
        normal = frame[0] * -sign
        force = on_geom2 * sign
        found.append(Contact(_geom_name(model, mine), _geom_name(model, other),
                             (float(contact.pos[0]), float(contact.pos[1]), float(contact.pos[2])),
                             (float(normal[0]), float(normal[1]), float(normal[2])), max(0.0, -float(contact.dist)),
                             (float(force[0]), float(force[1]), float(force[2]))))
    return found


def _geom_name(model: mujoco.MjModel, geom: int) -> str:
    return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, geom) or f"geom {geom}"
