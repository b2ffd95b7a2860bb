"""amcl, the node: localises a robot on a known map from its laser, odometry and tf.

    rosrun amcl amcl [scan:=...]

As navigation's amcl: the map from the `static_map` service (or the `map` topic with
~use_map_topic); `scan` (sensor_msgs/LaserScan), the odometry from tf (~odom_frame_id ->
~base_frame_id); publishes `amcl_pose` (geometry_msgs/PoseWithCovarianceStamped),
`particlecloud` (geometry_msgs/PoseArray) and the transform ~global_frame_id -> ~odom_frame_id
(stamped transform_tolerance ahead); listens to `initialpose` (a pose in ~global_frame_id, its
stamp's pose carried forward by the odometry since; one in another frame is ignored, as amcl's
handleInitialPoseMessage does; one that comes before the map is kept and set once the map is
here; its covariance's x-y block and yaw variance place the particles, as amcl reads it); serves
`global_localization` and `request_nomotion_update` (std_srvs/Empty). Each map (the first only
with ~first_map_only) places the particles by ~initial_pose_* and ~initial_cov_* as the parameter
server holds them then; every 1/~save_pose_rate seconds (default 0.5 Hz, none when not above 0),
on a scan that did not update the filter, and on Ctrl-C, amcl writes its pose and variances back
there, so an amcl restarted (or a new map) resumes where the robot was. The filter updates when the odometry moved
~update_min_d metres or turned ~update_min_a radians, resamples every ~resample_interval updates.
Parameters are amcl's, with its defaults; the filter itself is kame.nav.amcl. Its laser model is
the likelihood field (~laser_model_type's default, the TurtleBot's): amcl's `beam` and
`likelihood_field_prob` models are not implemented, and asking for either (or for a model amcl
does not know) says so once at start-up, naming the value, and runs the likelihood field.
What kame's amcl adds: a map without cells (0 x 0), or whose size, resolution or origin is not
usable, is refused with one error line (the filter keeps the map it had, or waits for one); an
initial pose or a scan with NaN or inf where a number must be is left out with a warning (at
most one each 10 s for scans), so the particles never become NaN; global_localization without a
map, or on one with no free cell, says so in one line.
"""

from __future__ import annotations

import math
import sys
import threading
from collections.abc import Sequence
from typing import Any

import numpy as np

from kame.client import clock, core, process, services, topics
from kame.client import log as _log
from kame.nav import inputs
from kame.nav.amcl import (
    INITIAL_POSE_PARAMS,
    FilterParams,
    LikelihoodField,
    ParticleFilter,
    angle_diff,
    filter_covariance,
    initial_hypothesis,
    message_covariance,
)
from kame.tf import errors as tf_errors
from kame.tf.transformations import euler_from_quaternion, quaternion_from_euler
from kame.tf_ros.buffer import Buffer
from kame.tf_ros.node_io import TransformBroadcaster, TransformListener

_FILTER_FIELDS = FilterParams.__dataclass_fields__
LASER_MODEL = "likelihood_field"
UNIMPLEMENTED_LASER_MODELS = ("beam", "likelihood_field_prob")


def _param(name: str, default: Any) -> Any:
    return process.get_param("~" + name, default)


def filter_params() -> FilterParams:
    values: dict[str, Any] = {}
    for name, spec in _FILTER_FIELDS.items():
        kind = int if spec.type in ("int", int) else str if spec.type in ("str", str) else float
        values[name] = kind(_param(name, spec.default))
    return FilterParams(**values)


def laser_model_warning(model: str) -> str | None:
    """What to tell a user whose ~laser_model_type is not the model this amcl runs (None when it is)."""
    if model == LASER_MODEL:
        return None
    if model in UNIMPLEMENTED_LASER_MODELS:
        return (f'~laser_model_type "{model}" is not implemented here; using the {LASER_MODEL} model instead '
                f'(its laser_z_hit, laser_z_rand, laser_sigma_hit and laser_likelihood_max_dist)')
    return f'Unknown laser model type "{model}"; defaulting to {LASER_MODEL} model'  # amcl's own words


def yaw_of(q: Any) -> float:
    return float(euler_from_quaternion((q.x, q.y, q.z, q.w))[2])


def compose(a: tuple[float, float, float], b: tuple[float, float, float]) -> tuple[float, float, float]:
    """a (+) b: pose b given in frame a."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], float(angle_diff(a[2] + b[2], 0.0))


def inverse(a: tuple[float, float, float]) -> tuple[float, float, float]:
    c, s = math.cos(a[2]), math.sin(a[2])
    return -c * a[0] - s * a[1], s * a[0] - c * a[1], -a[2]


class Amcl:
    def __init__(self) -> None:
        self.params = filter_params()
        # said once here: amcl reads the parameter only at start-up (and on dynamic_reconfigure,
        # which this amcl does not serve), so a beam-model launch file would otherwise run unnoticed
        warning = laser_model_warning(str(_param("laser_model_type", LASER_MODEL)))
        if warning is not None:
            _log.emit(_log.WARN, "%s", (warning,))
        self.global_frame = str(_param("global_frame_id", "map"))
        self.odom_frame = str(_param("odom_frame_id", "odom"))
        self.base_frame = str(_param("base_frame_id", "base_link"))
        self.update_min_d = float(_param("update_min_d", 0.2))
        self.update_min_a = float(_param("update_min_a", math.pi / 6.0))
        self.resample_interval = max(1, int(_param("resample_interval", 2)))
        self.transform_tolerance = float(_param("transform_tolerance", 0.1))
        self.laser_min_range = float(_param("laser_min_range", -1.0))
        self.laser_max_range = float(_param("laser_max_range", -1.0))
        self.tf_broadcast = bool(_param("tf_broadcast", True))
        save_pose_rate = float(_param("save_pose_rate", 0.5))
        self.save_pose_period = 1.0 / save_pose_rate if save_pose_rate > 0 else -1.0
        self.last_save = 0.0  # ROS time, seconds: as amcl, the first chance to save takes it
        self.first_map_only = bool(_param("first_map_only", False))
        self.lock = threading.Lock()
        self.filter: ParticleFilter | None = None
        # an /initialpose that came before the map, set once the map is here (initial_pose_hyp_)
        self.pending_pose: tuple[tuple[float, float, float], np.ndarray] | None = None
        self.last_covariance: np.ndarray | None = None  # of the last amcl_pose published
        self.last_odom: tuple[float, float, float] | None = None  # at the last filter update
        self.latest_odom: tuple[float, float, float] | None = None  # at the latest scan
        self.force_update = True
        self.updates = 0
        self.map_to_odom: tuple[float, float, float] | None = None
        self.sent_first_transform = False
        node = core.get_node()
        assert node is not None
        self.buffer = Buffer(warn=lambda text: _log.emit(_log.WARN, text, ()),
                             error=lambda text: _log.emit(_log.ERROR, text, ()))
        self.listener = TransformListener(node, self.buffer, now=lambda: clock.get_rostime().to_nsec())
        self.broadcaster = TransformBroadcaster(node)
        from geometry_msgs.msg import PoseArray, PoseWithCovarianceStamped
        self.pose_pub = topics.Publisher("amcl_pose", PoseWithCovarianceStamped, queue_size=2, latch=True)
        self.cloud_pub = topics.Publisher("particlecloud", PoseArray, queue_size=2, latch=True)

    # ---------------------------------------------------------------- inputs

    def on_map(self, msg: Any) -> None:
        """The `map` topic's callback (~use_map_topic); ~first_map_only keeps the first."""
        if self.first_map_only and self.filter is not None:
            return
        self.set_map(msg)

    def _initial_from_server(self) -> tuple[tuple[float, float, float], np.ndarray]:
        """~initial_pose_* and ~initial_cov_*, read afresh each time a map arrives as amcl does: what
        this amcl saved there (~save_pose_rate) or a user set since it started places a new map's
        particles."""
        mean, covariance, warnings = initial_hypothesis([float(_param(name, default))
                                                         for name, default, _ in INITIAL_POSE_PARAMS])
        for warning in warnings:
            _log.emit(_log.WARN, "%s", (warning,))
        return mean, covariance

    def set_map(self, msg: Any) -> None:
        info = msg.info
        data = msg.data
        problem = inputs.map_problem(info, len(data))
        if problem is not None:
            kept = "keeping the map it had" if self.filter is not None else "waiting for a usable map"
            _log.emit(_log.ERROR, "Ignoring the map: %s; amcl is %s", (problem, kept))
            return
        cells = np.frombuffer(data, dtype=np.int8) if isinstance(data, bytes) else np.asarray(data, np.int16)
        cells = cells.reshape(info.height, info.width)
        field = LikelihoodField(cells, info.resolution, (info.origin.position.x, info.origin.position.y),
                                self.params.laser_likelihood_max_dist)
        mean, covariance = self._initial_from_server()
        with self.lock:
            self.filter = ParticleFilter(self.params, field, seed=int(_param("seed", 0)))
            self.filter.set_gaussian(mean, covariance)
            self._restart_filter()
            self._apply_pending_pose()
        _log.emit(_log.INFO, "Received a %d X %d map @ %.3f m/pix", (info.width, info.height, info.resolution))

    def _restart_filter(self) -> None:
        """After the particles are placed anew (amcl's pf_init_ = false): the next scan weighs them
        where they are, without the odometry's motion since the last update (an initial pose
        already carries it), and restarts the resampling count."""
        self.last_odom = None
        self.force_update = True
        self.updates = 0

    def _apply_pending_pose(self) -> None:
        """amcl's applyInitialPose: the waiting initial pose, once there is a map to place it on."""
        if self.pending_pose is not None and self.filter is not None:
            self.filter.set_gaussian(*self.pending_pose)
            self.pending_pose = None
            self._restart_filter()

    def on_initial_pose(self, msg: Any) -> None:
        frame = msg.header.frame_id
        frame = frame[1:] if frame.startswith("/") else frame  # amcl's stripSlash: one leading slash
        if not frame:
            _log.emit(_log.WARN, "Received initial pose with empty frame_id.  You should always supply a frame_id.",
                      ())
        elif frame != self.global_frame:
            _log.emit(_log.WARN, 'Ignoring initial pose in frame "%s"; initial poses must be in the global frame, '
                      '"%s"', (frame, self.global_frame))
            return
        pose = msg.pose.pose
        problem = inputs.pose_problem(pose) or inputs.covariance_problem(msg.pose.covariance)
        if problem is not None:
            _log.emit(_log.WARN, "Ignoring initial pose: %s", (problem,))
            return
        mean = compose((pose.position.x, pose.position.y, yaw_of(pose.orientation)),
                       self._moved_since(msg.header.stamp))
        _log.emit(_log.INFO, "Setting pose (%.6f): %.3f %.3f %.3f", (clock.get_rostime().to_sec(), *mean))
        with self.lock:
            self.pending_pose = (mean, filter_covariance(msg.pose.covariance))
            self._apply_pending_pose()

    def _moved_since(self, stamp: Any) -> tuple[float, float, float]:
        """The base's motion in odom from `stamp` to now, as a pose in the base at `stamp`: a pose
        estimate made in the past (an rviz click, then the robot drove on) is carried forward by
        it. Identity for a zero stamp (no time given) or when tf cannot say (amcl's fallback; a
        failure before amcl has sent its own transform is start-up, not worth a warning)."""
        if stamp.secs == 0 and stamp.nsecs == 0:
            return 0.0, 0.0, 0.0
        try:
            found = self.buffer.lookup_transform_full(self.base_frame, stamp, self.base_frame, clock.get_rostime(),
                                                      self.odom_frame, clock.Duration(0.5))
        except tf_errors.TransformException as exc:
            if self.sent_first_transform:
                _log.emit(_log.WARN, "Failed to transform initial pose in time (%s)", (exc,))
            return 0.0, 0.0, 0.0
        t = found.transform.translation
        return t.x, t.y, yaw_of(found.transform.rotation)

    def global_localization(self, _request: Any) -> Any:
        from std_srvs.srv import EmptyResponse
        with self.lock:
            if self.filter is None:
                _log.emit(_log.WARN, "global_localization: there is no map yet to spread the particles over", ())
                return EmptyResponse()
            _log.emit(_log.INFO, "Initializing with uniform distribution", ())
            try:
                self.filter.set_uniform()
            except ValueError as exc:  # no free cell: the particles stay where they were
                _log.emit(_log.ERROR, "global_localization: %s", (exc,))
                return EmptyResponse()
            self._restart_filter()
        return EmptyResponse()

    def nomotion_update(self, _request: Any) -> Any:
        from std_srvs.srv import EmptyResponse
        with self.lock:
            self.force_update = True
        return EmptyResponse()

    def _pose_of(self, target: str, source: str, stamp: Any) -> tuple[float, float, float]:
        found = self.buffer.lookup_transform(target, source, stamp, clock.Duration(0.2))
        t, q = found.transform.translation, found.transform.rotation
        return t.x, t.y, yaw_of(q)

    def on_scan(self, scan: Any) -> None:
        problem = inputs.scan_problem(scan)
        if problem is not None:
            _log.emit_throttle(10.0, _log.WARN, "Ignoring a scan in frame %s: %s", (scan.header.frame_id, problem))
            return
        try:
            odom = self._pose_of(self.odom_frame, self.base_frame, scan.header.stamp)
            laser = self._pose_of(self.base_frame, scan.header.frame_id, scan.header.stamp)
        except tf_errors.TransformException as exc:
            _log.emit_throttle(5.0, _log.WARN, "Failed to compute odom pose, skipping scan (%s)", (exc,))
            return
        ranges = np.asarray(scan.ranges, dtype=float)
        angles = scan.angle_min + scan.angle_increment * np.arange(len(ranges))
        # as amcl: laser_max_range can only shorten the scanner's range (the TurtleBot's 12 m
        # against the Kinect's 10 m must not make a 10 m no-return reading count as a wall)
        range_max = min(self.laser_max_range, float(scan.range_max)) if self.laser_max_range > 0 \
            else float(scan.range_max)
        range_min = max(self.laser_min_range, float(scan.range_min))
        ranges = np.where(ranges < range_min, np.nan, ranges)
        save: dict[str, float] | None = None
        with self.lock:
            pf = self.filter
            if pf is None:
                return
            self.latest_odom = odom
            moved = self.last_odom is None or math.hypot(odom[0] - self.last_odom[0], odom[1] - self.last_odom[1]) \
                >= self.update_min_d or abs(float(angle_diff(odom[2], self.last_odom[2]))) >= self.update_min_a
            if moved or self.force_update:
                if self.last_odom is not None:
                    pf.predict(self.last_odom, odom)
                self.last_odom = odom
                self.force_update = False
                pf.weigh(ranges, angles, range_max, laser)
                self.updates += 1
                if self.updates % self.resample_interval == 0:
                    pf.resample()
                estimate = pf.estimate()
                base = (estimate.x, estimate.y, estimate.theta)
                self.map_to_odom = compose(base, inverse(odom))
                self._publish_estimate(scan.header.stamp, estimate, pf.particles)
            elif self.map_to_odom is not None and self.save_pose_period > 0:
                # as amcl: saved from a scan that did not update the filter, at most every period
                now = clock.get_rostime().to_sec()
                if now - self.last_save >= self.save_pose_period:
                    self.last_save = now
                    save = self._pose_to_save(odom)
            if self.map_to_odom is not None and self.tf_broadcast:
                self._publish_transform(scan.header.stamp)
        if save is not None:
            self._save(save)

    # ---------------------------------------------------------------- the pose kept for a restart

    def _pose_to_save(self, odom: tuple[float, float, float]) -> dict[str, float] | None:
        """amcl's savePoseToServer: the robot's pose in the map now (the last map -> odom transform
        applied to the odometry of the latest scan) with the last amcl_pose's variances."""
        if self.map_to_odom is None or self.last_covariance is None:
            return None
        x, y, yaw = compose(self.map_to_odom, odom)
        cov = self.last_covariance
        return {"initial_pose_x": x, "initial_pose_y": y, "initial_pose_a": yaw,
                "initial_cov_xx": float(cov[0, 0]), "initial_cov_yy": float(cov[1, 1]),
                "initial_cov_aa": float(cov[2, 2])}

    def _save(self, values: dict[str, float]) -> None:
        for name, value in values.items():
            process.set_param("~" + name, value)

    def save_on_interrupt(self, reason: str) -> None:
        """amcl saves its pose once more when Ctrl-C (or roslaunch's SIGINT) stops it."""
        if reason not in ("signal-2", "keyboard interrupt"):
            return
        with self.lock:
            save = None if self.latest_odom is None else self._pose_to_save(self.latest_odom)
        if save is not None:
            self._save(save)

    # ---------------------------------------------------------------- outputs

    def _publish_estimate(self, stamp: Any, estimate: Any, particles: np.ndarray) -> None:
        from geometry_msgs.msg import Pose, PoseArray, PoseWithCovarianceStamped
        msg = PoseWithCovarianceStamped()
        msg.header.stamp, msg.header.frame_id = stamp, self.global_frame
        msg.pose.pose = _pose(estimate.x, estimate.y, estimate.theta, Pose)
        msg.pose.covariance = message_covariance(estimate.covariance)
        self.last_covariance = estimate.covariance
        self.pose_pub.publish(msg)
        cloud = PoseArray()
        cloud.header.stamp, cloud.header.frame_id = stamp, self.global_frame
        cloud.poses = [_pose(float(x), float(y), float(t), Pose) for x, y, t in particles]
        self.cloud_pub.publish(cloud)

    def _publish_transform(self, stamp: Any) -> None:
        from geometry_msgs.msg import TransformStamped
        assert self.map_to_odom is not None
        x, y, theta = self.map_to_odom
        t = TransformStamped()
        t.header.stamp = clock.Time.from_sec(stamp.to_sec() + self.transform_tolerance)
        t.header.frame_id, t.child_frame_id = self.global_frame, self.odom_frame
        t.transform.translation.x, t.transform.translation.y = x, y
        q = quaternion_from_euler(0.0, 0.0, theta)
        t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z, t.transform.rotation.w = \
            (float(v) for v in q)
        self.broadcaster.send_transform(t)
        self.sent_first_transform = True


def _pose(x: float, y: float, theta: float, pose_class: type[Any]) -> Any:
    pose = pose_class()
    pose.position.x, pose.position.y = x, y
    pose.orientation.z, pose.orientation.w = math.sin(theta / 2), math.cos(theta / 2)
    return pose


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    _log.use_roscpp_console()
    process.init_node("amcl", argv=argv)
    from geometry_msgs.msg import PoseWithCovarianceStamped
    from nav_msgs.msg import OccupancyGrid
    from nav_msgs.srv import GetMap
    from sensor_msgs.msg import LaserScan
    from std_srvs.srv import Empty

    amcl = Amcl()
    core.add_preshutdown_hook(amcl.save_on_interrupt)
    # before the map: amcl keeps a pose that comes while it waits and places it on the map
    topics.Subscriber("initialpose", PoseWithCovarianceStamped, amcl.on_initial_pose, queue_size=2)
    if bool(_param("use_map_topic", False)):
        topics.Subscriber("map", OccupancyGrid, amcl.on_map, queue_size=1)
        _log.emit(_log.INFO, "Subscribed to map topic.", ())
    else:
        _log.emit(_log.INFO, "Requesting the map...", ())
        get_map = services.ServiceProxy("static_map", GetMap)
        while True:
            try:
                answer = get_map()
                break
            except Exception:  # no static_map yet, or map_server failing the call: amcl asks again
                if core.is_shutdown():
                    return 0
                _log.emit(_log.WARN, "Request for map failed; trying again...", ())
                if core.wait_for_shutdown(0.5):
                    return 0
        amcl.set_map(answer.map)
    topics.Subscriber("scan", LaserScan, amcl.on_scan, queue_size=1)
    services.Service("global_localization", Empty, amcl.global_localization)
    services.Service("request_nomotion_update", Empty, amcl.nomotion_update)
    process.spin()
    return 0
