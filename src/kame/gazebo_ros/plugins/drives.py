"""The drive plugins: diff_drive, skid_steer_drive and planar_move, and what the Kobuki's
(kame.gazebo_ros.plugins.kobuki) drives with, with odometry and tf as they publish them.

diff_drive, Kobuki's and skid_steer_drive turn the wheel joints: each wheel joint's velocity actuator is
asked for the wheel's speed (up to wheelTorque, at most wheelAcceleration faster each second),
and the world's physics moves the robot on its wheels. planar_move sets the model's velocity in
the plane directly, as Gazebo's does. Odometry is the model's pose in the world (gazebo_ros's
default odometrySource, "world"), or for diff_drive with odometrySource "encoder" the wheels'
turns integrated.
"""

from __future__ import annotations

import math
import threading
from typing import Any

from kame.client import process
from kame.gazebo.poses import Pose
from kame.gazebo_ros.conversions import stamp
from kame.gazebo_ros.plugins.base import Every, GazeboPlugin, PluginContext
from kame.gazebo_ros.plugins.parameters import PluginParameterError

# gazebo_ros_skid_steer_drive and planar_move print their own missing-parameter lines
SKID_MISSING = 'GazeboRosSkidSteerDrive Plugin (ns = {ns}) missing <{tag}>, defaults to "{default}"'
PLANAR_MISSING = "PlanarMovePlugin (ns = {ns}) missing <{tag}>, defaults to {default}"
KOBUKI_MISSING = "{info}: couldn't find <{tag}>, using {default}"


def yaw_of(pose: Pose) -> float:
    x, y, z, w = pose.orientation
    return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


class _Command:
    """The newest cmd_vel (linear.x, linear.y, angular.z), written by the subscriber's thread, which
    never touches the World (only the stepping thread does): it stamps a command with the simulated
    time of the plugin's last update."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self.x = self.y = self.rotation = 0.0
        self.received = -math.inf

    def set(self, msg: Any, now: float) -> None:
        values = (msg.linear.x, msg.linear.y, msg.angular.z)
        if not all(math.isfinite(v) for v in values):
            return
        with self._lock:
            self.x, self.y, self.rotation = values
            self.received = now

    def get(self) -> tuple[float, float, float]:
        with self._lock:
            return self.x, self.y, self.rotation

    def stop(self) -> None:
        with self._lock:
            self.x = self.y = self.rotation = 0.0


def _tf_prefix(namespace: str) -> str:
    """tf::getPrefixParam: ~tf_prefix searched up from the robot's namespace ("" when unset)."""
    parts = [p for p in namespace.split("/") if p]
    for depth in range(len(parts), -1, -1):
        found = process.get_param("/" + "/".join([*parts[:depth], "tf_prefix"]), None)
        if isinstance(found, str):
            return found
    return ""


class _Odometry:
    """Odometry and the odom -> base transform, published as the drive plugins do."""

    def __init__(self, plugin: GazeboPlugin, namespace: str, topic: str, odom_frame: str, base_frame: str,
                 publish_tf: bool, covariance: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> None:
        from nav_msgs.msg import Odometry
        from tf2_msgs.msg import TFMessage

        self.namespace = namespace
        self.tf_prefix = _tf_prefix(namespace)
        self.odom_frame = self._framed(odom_frame)
        self.base_frame = self._framed(base_frame)
        self.covariance = covariance
        self.odometry = plugin.own(plugin.context.publisher(namespace, topic, Odometry))
        self.tf = plugin.own(plugin.context.publisher("", "/tf", TFMessage)) if publish_tf else None

    def _framed(self, frame: str) -> str:
        """tf::resolve(tf_prefix, frame), as gazebo_ros's resolveTF: an absolute frame loses its
        slash, a relative one takes the tf_prefix found from the robot's namespace (none: as is)."""
        if frame.startswith("/") or not self.tf_prefix:
            return frame.lstrip("/")
        return f"{self.tf_prefix.lstrip('/')}/{frame}"

    def publish(self, now: float, pose: Pose, linear: tuple[float, float], angular: float) -> None:
        from geometry_msgs.msg import TransformStamped
        from nav_msgs.msg import Odometry
        from tf2_msgs.msg import TFMessage

        time_stamp = stamp(now)
        if self.tf is not None:
            t = TransformStamped()
            t.header.stamp = time_stamp
            t.header.frame_id = self.odom_frame
            t.child_frame_id = self.base_frame
            t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = pose.position
            (t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z,
             t.transform.rotation.w) = pose.orientation
            self.tf.publish(TFMessage([t]))
        msg = Odometry()
        msg.header.stamp = time_stamp
        msg.header.frame_id = self.odom_frame
        msg.child_frame_id = self.base_frame
        msg.pose.pose.position.x, msg.pose.pose.position.y, msg.pose.pose.position.z = pose.position
        (msg.pose.pose.orientation.x, msg.pose.pose.orientation.y, msg.pose.pose.orientation.z,
         msg.pose.pose.orientation.w) = pose.orientation
        cx, cy, cyaw = self.covariance
        covariance = [0.0] * 36
        covariance[0], covariance[7], covariance[14] = cx, cy, 1e6 if any(self.covariance) else 0.0
        covariance[21], covariance[28], covariance[35] = (1e6, 1e6, cyaw) if any(self.covariance) else (0, 0, 0)
        msg.pose.covariance = covariance
        msg.twist.covariance = covariance
        msg.twist.twist.linear.x, msg.twist.twist.linear.y = linear
        msg.twist.twist.angular.z = angular
        self.odometry.publish(msg)


class _WheelDrive(GazeboPlugin):
    """What diff_drive and skid_steer_drive share: wheels on two sides turned to follow cmd_vel."""

    info: str
    left: list[str]
    right: list[str]
    separation: float
    diameter: float
    torque: float
    acceleration: float
    legacy: bool
    timeout = math.inf  # seconds of simulated time without a command before the wheels stop

    def _start_drive(self, namespace: str, command_topic: str, rate: float) -> None:
        from geometry_msgs.msg import Twist

        model = self.context.model
        names = {j.name for j in model.joints if j.type in ("revolute", "continuous")} if model is not None else set()
        for joint in (*self.left, *self.right):
            if joint not in names:
                raise PluginParameterError(f"{self.info}: couldn't get wheel hinge joint named \"{joint}\"")
        self.command = _Command()
        self.rate = Every(rate)
        self.speeds = [0.0, 0.0]  # left, right: the wheels' surface speeds asked of the actuators
        self.last_update = self.context.world.sim_time
        self.context.info(f"{self.info}: Try to subscribe to {command_topic}")
        self.own(self.context.subscriber(namespace, command_topic, Twist,
                                         lambda msg: self.command.set(msg, self.last_update)))
        self.context.info(f"{self.info}: Subscribe to {command_topic}")

    def _targets(self) -> tuple[float, float]:
        x, _, rotation = self.command.get()
        half = rotation * self.separation / 2.0
        if self.legacy:  # gazebo_ros's legacyMode: the wheels swapped, as robots written for it expect
            return x + half, x - half
        return x - half, x + half

    def _drive(self, now: float) -> None:
        if now - self.command.received > self.timeout:
            self.command.stop()
        targets = self._targets()
        elapsed = max(0.0, now - self.last_update)
        self.last_update = now
        for side, target in enumerate(targets):
            if self.acceleration > 0:
                step = self.acceleration * elapsed
                target = min(max(target, self.speeds[side] - step), self.speeds[side] + step)
            self.speeds[side] = target
        radius = self.diameter / 2.0
        world = self.context.world
        for joints, speed in ((self.left, self.speeds[0]), (self.right, self.speeds[1])):
            for joint in joints:
                world.drive_joint(self.context.scoped(joint), speed / radius, self.torque)

    def reset(self) -> None:
        self.command.stop()
        self.speeds = [0.0, 0.0]
        self.last_update = self.context.world.sim_time
        self.rate.restart()


class TwoWheelDrive(_WheelDrive):
    """What diff_drive and Kobuki's plugin share: two wheels, odometry from the world or the
    wheels' encoders, the wheels' joint states."""

    publish_wheel_joint_state: bool
    encoder: bool

    def _start_two_wheels(self, namespace: str, command_topic: str, rate: float, odometry_topic: str,
                          odometry_frame: str, base_frame: str, publish_odom_tf: bool) -> None:
        self._start_drive(namespace, command_topic, rate)
        self.odom = _Odometry(self, namespace, odometry_topic, odometry_frame, base_frame, publish_odom_tf)
        self.context.info(f"{self.info}: Advertise odom on {odometry_topic} ")
        self.joint_states: Any = None
        if self.publish_wheel_joint_state:
            from sensor_msgs.msg import JointState

            self.joint_states = self.own(self.context.publisher(namespace, "joint_states", JointState))
        self._encoder_pose = (0.0, 0.0, 0.0)

    def update(self, now: float) -> None:
        if self.rate.due(now):
            self.step_wheels(now)

    def step_wheels(self, now: float) -> None:
        """The wheels driven as commanded, odometry and the wheels' joint states published."""
        elapsed = now - self.last_update
        self._drive(now)
        world = self.context.world
        model = self.context.model_name()
        if self.encoder:
            self._integrate(elapsed)
            x, y, yaw = self._encoder_pose
            pose = Pose((x, y, 0.0), (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)))
            linear = ((self.speeds[0] + self.speeds[1]) / 2, 0.0)
            angular = (self.speeds[1] - self.speeds[0]) / self.separation * (-1 if self.legacy else 1)
        else:
            state = world.model_state(model)
            pose = state.pose
            (vx, vy, _), angular = state.linear, state.angular[2]
            yaw = yaw_of(pose)
            linear = (vx * math.cos(yaw) + vy * math.sin(yaw), -vx * math.sin(yaw) + vy * math.cos(yaw))
        self.odom.publish(now, pose, linear, angular)
        if self.joint_states is not None:
            from sensor_msgs.msg import JointState

            joints = [*self.left, *self.right]
            msg = JointState()
            msg.header.stamp = stamp(now)
            msg.name = joints
            msg.position = [world.joint_state(self.context.scoped(j)).position[0] for j in joints]
            self.joint_states.publish(msg)

    def _integrate(self, elapsed: float) -> None:
        """The wheels' measured turns since the last update, as dead reckoning."""
        world = self.context.world
        radius = self.diameter / 2.0
        left = world.joint_state(self.context.scoped(self.left[0])).velocity[0] * radius
        right = world.joint_state(self.context.scoped(self.right[0])).velocity[0] * radius
        if self.legacy:
            left, right = right, left
        distance = (left + right) / 2 * elapsed
        turn = (right - left) / self.separation * elapsed
        x, y, yaw = self._encoder_pose
        self._encoder_pose = (x + distance * math.cos(yaw + turn / 2), y + distance * math.sin(yaw + turn / 2),
                              yaw + turn)

    def reset_encoders(self) -> None:
        self._encoder_pose = (0.0, 0.0, 0.0)

    def reset(self) -> None:
        super().reset()
        self.reset_encoders()


class DiffDrive(TwoWheelDrive):
    """libgazebo_ros_diff_drive.so."""

    def __init__(self, context: PluginContext) -> None:
        super().__init__(context)
        probe = context.parameters("DiffDrive")
        namespace = context.namespace(probe)
        self.info = f"DiffDrive(ns = /{namespace}/)" if namespace else "DiffDrive(ns = //)"
        p = context.parameters(self.info)
        self.left = [p.text("leftJoint", "left_joint")]
        self.right = [p.text("rightJoint", "right_joint")]
        self.separation = p.number("wheelSeparation", 0.34)
        self.diameter = p.number("wheelDiameter", 0.15)
        self.acceleration = p.number("wheelAcceleration", 0.0)
        self.torque = p.number("wheelTorque", 5.0)
        command_topic = p.text("commandTopic", "cmd_vel")
        odometry_topic = p.text("odometryTopic", "odom")
        odometry_frame = p.text("odometryFrame", "odom")
        base_frame = p.text("robotBaseFrame", "base_footprint")
        self.publish_wheel_tf = p.flag("publishWheelTF", False)
        self.publish_wheel_joint_state = p.flag("publishWheelJointState", False)
        self.legacy = p.flag("legacyMode", True)
        publish_odom_tf = p.flag("publishOdomTF", True)
        rate = p.number("updateRate", 100.0)
        source = p.text("odometrySource", "world").lower()
        if source not in ("world", "encoder"):
            raise PluginParameterError(f"{self.info}: <odometrySource> must be world or encoder, not {source!r}")
        self.encoder = source == "encoder"
        if self.diameter <= 0 or self.separation <= 0:
            raise PluginParameterError(f"{self.info}: <wheelDiameter> and <wheelSeparation> must be above 0")
        context.report(p)
        self._start_two_wheels(namespace, command_topic, rate, odometry_topic, odometry_frame, base_frame,
                               publish_odom_tf)


class SkidSteerDrive(_WheelDrive):
    """libgazebo_ros_skid_steer_drive.so: four wheels, two a side."""

    def __init__(self, context: PluginContext) -> None:
        super().__init__(context)
        probe = context.parameters("GazeboRosSkidSteerDrive")
        namespace = context.namespace(probe)
        self.info = f"GazeboRosSkidSteerDrive Plugin (ns = {namespace})"
        p = context.parameters(self.info, SKID_MISSING.replace("{ns}", namespace))
        self.left = [p.text("leftFrontJoint", "left_front_joint"), p.text("leftRearJoint", "left_rear_joint")]
        self.right = [p.text("rightFrontJoint", "right_front_joint"), p.text("rightRearJoint", "right_rear_joint")]
        self.separation = p.number("wheelSeparation", 0.4)
        self.diameter = p.number("wheelDiameter", 0.15)
        self.torque = p.number("torque", 5.0)
        self.acceleration = 0.0
        self.legacy = False
        command_topic = p.text("commandTopic", "cmd_vel")
        odometry_topic = p.text("odometryTopic", "odom")
        odometry_frame = p.text("odometryFrame", "odom")
        base_frame = p.text("robotBaseFrame", "base_footprint")
        rate = p.number("updateRate", 100.0)
        broadcast_tf = p.flag("broadcastTF", False)
        covariance = (p.number("covariance_x", 0.0001), p.number("covariance_y", 0.0001),
                      p.number("covariance_yaw", 0.01))
        if self.diameter <= 0 or self.separation <= 0:
            raise PluginParameterError(f"{self.info}: <wheelDiameter> and <wheelSeparation> must be above 0")
        context.report(p)
        self._start_drive(namespace, command_topic, rate)
        self.odom = _Odometry(self, namespace, odometry_topic, odometry_frame, base_frame, broadcast_tf, covariance)

    def update(self, now: float) -> None:
        if not self.rate.due(now):
            return
        self._drive(now)
        world = self.context.world
        model = self.context.model_name()
        state = world.model_state(model)
        (vx, vy, _), yaw = state.linear, yaw_of(state.pose)
        self.odom.publish(now, state.pose, (vx * math.cos(yaw) + vy * math.sin(yaw),
                                            -vx * math.sin(yaw) + vy * math.cos(yaw)), state.angular[2])


class PlanarMove(GazeboPlugin):
    """libgazebo_ros_planar_move.so: the model moves in the plane as cmd_vel says (x, y, yaw rate)."""

    def __init__(self, context: PluginContext) -> None:
        from geometry_msgs.msg import Twist

        super().__init__(context)
        probe = context.parameters("PlanarMovePlugin")
        namespace = context.namespace(probe)
        p = context.parameters("PlanarMovePlugin", PLANAR_MISSING.replace("{ns}", namespace))
        command_topic = p.text("commandTopic", "cmd_vel")
        odometry_topic = p.text("odometryTopic", "odom")
        odometry_frame = p.text("odometryFrame", "odom")
        base_frame = p.text("robotBaseFrame", "base_footprint")
        self.odometry_rate = Every(p.number("odometryRate", 20.0))
        publish_tf = p.flag("publishOdomTF", True, quiet=True)
        self.timeout = p.number("cmdTimeout", -1.0, quiet=True)
        context.report(p)
        self.command = _Command()
        self.now = context.world.sim_time  # the world's time at the last update: callbacks never touch the World
        self.own(context.subscriber(namespace, command_topic, Twist, lambda msg: self.command.set(msg, self.now)))
        self.odom = _Odometry(self, namespace, odometry_topic, odometry_frame, base_frame, publish_tf)

    def update(self, now: float) -> None:
        self.now = now
        world = self.context.world
        model = self.context.model_name()
        if self.timeout > 0 and now - self.command.received > self.timeout:
            self.command.stop()
        x, y, rotation = self.command.get()
        state = world.model_state(model)
        pose, yaw = state.pose, yaw_of(state.pose)
        world.set_model_twist(model, (x * math.cos(yaw) - y * math.sin(yaw), y * math.cos(yaw) + x * math.sin(yaw),
                                      state.linear[2]), (0.0, 0.0, rotation))
        if self.odometry_rate.due(now):
            self.odom.publish(now, pose, (x, y), rotation)

    def reset(self) -> None:
        self.command.stop()
        self.odometry_rate.restart()
