"""Plugins that read a model's bodies and joints: imu (the model plugin: a link's orientation,
rates and accelerations from its motion), imu_sensor (an <imu> sensor's reading), p3d (ground
truth as nav_msgs/Odometry), bumper (a contact sensor's contacts as gazebo_msgs/ContactsState)
and joint_state_publisher (sensor_msgs/JointState of the named joints).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from kame.gazebo.poses import Pose
from kame.gazebo_ros import relative
from kame.gazebo_ros.conversions import stamp
from kame.gazebo_ros.plugins.base import Every, GazeboPlugin, PluginContext
from kame.gazebo_ros.plugins.parameters import Parameters, PluginParameterError


def _offset(p: Parameters, xyz_tag: str, rpy_tag: str) -> Pose:
    x, y, z = p.vector(xyz_tag, (0.0, 0.0, 0.0), quiet=True)
    roll, pitch, yaw = p.vector(rpy_tag, (0.0, 0.0, 0.0), quiet=True)
    return Pose.from_xyz_rpy(x, y, z, roll, pitch, yaw)


def _required(p: Parameters, tag: str, what: str) -> str:
    if not p.has(tag):
        raise PluginParameterError(f"{what} plugin missing <{tag}>, cannot proceed")
    return p.text(tag, "")


def _covariance(stddev: float) -> list[float]:
    variance = stddev * stddev
    return [variance, 0.0, 0.0, 0.0, variance, 0.0, 0.0, 0.0, variance]


class Imu(GazeboPlugin):
    """libgazebo_ros_imu.so: a link's orientation, angular velocity and linear acceleration (its
    change of velocity, without gravity, as GazeboRosIMU differentiates it), in the link's frame."""

    def __init__(self, context: PluginContext) -> None:
        from sensor_msgs.msg import Imu as ImuMsg

        super().__init__(context)
        p = context.parameters("imu", "imu plugin missing <{tag}>, defaults to {default}")
        namespace = context.namespace(p)
        self.link = context.scoped(_required(p, "bodyName", "imu"))
        topic = p.text("topicName", "/default_imu")
        self.frame = p.text("frameName", self.link.rpartition("::")[2], quiet=True).lstrip("/")
        self.offset = _offset(p, "xyzOffset", "rpyOffset")
        self.noise = p.number("gaussianNoise", 0.0)
        self.rate = Every(p.number("updateRate", 0.0, quiet=True))
        context.report(p)
        self._check_link()
        self.imu = self.own(context.publisher(namespace, topic, ImuMsg))
        self._last: tuple[float, tuple[float, float, float]] | None = None

    def _check_link(self) -> None:
        model = self.context.model
        if model is None or model.link(self.link.rpartition("::")[2]) is None:
            raise PluginParameterError(f"imu plugin error: bodyName: {self.link.rpartition('::')[2]} does not exist")

    def reset(self) -> None:
        self._last = None
        self.rate.restart()

    def update(self, now: float) -> None:
        if not self.rate.due(now):
            return
        from sensor_msgs.msg import Imu as ImuMsg

        state = self.context.world.link_state(self.link)
        pose = Pose(state.pose.position, relative.normalized(
            relative.carried_into_world(self.offset, state.pose).orientation))
        previous, self._last = self._last, (now, state.linear)
        if previous is None or now <= previous[0]:
            acceleration = (0.0, 0.0, 0.0)
        else:
            dt = now - previous[0]
            acceleration = relative.unrotate(pose, tuple((a - b) / dt for a, b in zip(state.linear, previous[1],
                                                                                       strict=True)))
        rates = relative.unrotate(pose, state.angular)
        rng = self.context.world.rng
        noisy = [v + (float(rng.normal(0.0, self.noise)) if self.noise > 0 else 0.0) for v in (*rates, *acceleration)]
        msg = ImuMsg()
        msg.header.stamp = stamp(now)
        msg.header.frame_id = self.frame
        msg.orientation.x, msg.orientation.y, msg.orientation.z, msg.orientation.w = pose.orientation
        msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z = noisy[:3]
        msg.linear_acceleration.x, msg.linear_acceleration.y, msg.linear_acceleration.z = noisy[3:]
        msg.orientation_covariance = _covariance(self.noise)
        msg.angular_velocity_covariance = _covariance(self.noise)
        msg.linear_acceleration_covariance = _covariance(self.noise)
        self.imu.publish(msg)


class ImuSensor(GazeboPlugin):
    """libgazebo_ros_imu_sensor.so: an <imu> sensor's reading (gravity's reaction included)."""

    def __init__(self, context: PluginContext) -> None:
        from sensor_msgs.msg import Imu as ImuMsg

        super().__init__(context)
        sensor = context.sensor()
        if sensor is None or sensor.type != "imu":
            raise PluginParameterError("imu_sensor plugin must sit in an imu sensor (<sensor type=\"imu\">)")
        self.sensor_info = context.sensor_info()
        p = context.parameters("GazeboRosImuSensor", "GazeboRosImuSensor missing <{tag}>, defaults to {default}")
        namespace = context.namespace(p)
        topic = p.text("topicName", "imu")
        self.frame = p.text("frameName", p.text("bodyName", context.plugin.link, quiet=True), quiet=True).lstrip("/")
        self.noise = p.number("gaussianNoise", 0.0, quiet=True)
        rate = p.number("updateRateHZ", 1.0)
        self.rate = Every(rate)
        context.report(p)
        self.imu = self.own(context.publisher(namespace, topic, ImuMsg))

    def update(self, now: float) -> None:
        if not self.rate.due(now):
            return
        from sensor_msgs.msg import Imu as ImuMsg

        reading = self.context.world.imu_reading(self.sensor_info)
        rng = self.context.world.rng
        extra = rng.normal(0.0, self.noise, 6) if self.noise > 0 else np.zeros(6)
        msg = ImuMsg()
        msg.header.stamp = stamp(now)
        msg.header.frame_id = self.frame
        msg.orientation.x, msg.orientation.y, msg.orientation.z, msg.orientation.w = reading.orientation
        (msg.angular_velocity.x, msg.angular_velocity.y,
         msg.angular_velocity.z) = (float(v + e) for v, e in zip(reading.angular_velocity, extra[:3], strict=True))
        (msg.linear_acceleration.x, msg.linear_acceleration.y,
         msg.linear_acceleration.z) = (float(v + e) for v, e in zip(reading.linear_acceleration, extra[3:],
                                                                      strict=True))
        msg.angular_velocity_covariance = _covariance(self.noise)
        msg.linear_acceleration_covariance = _covariance(self.noise)
        self.imu.publish(msg)


class P3d(GazeboPlugin):
    """libgazebo_ros_p3d.so: a link's true pose and twist, in the world or another link's frame."""

    def __init__(self, context: PluginContext) -> None:
        from nav_msgs.msg import Odometry

        super().__init__(context)
        p = context.parameters("p3d", "p3d plugin missing <{tag}>, defaults to {default}")
        namespace = context.namespace(p)
        body = _required(p, "bodyName", "p3d")
        topic = _required(p, "topicName", "p3d")
        self.link = context.scoped(body)
        self.frame = p.text("frameName", "world")
        self.child_frame = body
        self.offset = _offset(p, "xyzOffsets", "rpyOffsets")
        self.noise = p.number("gaussianNoise", 0.0)
        self.rate = Every(p.number("updateRate", 0.0, quiet=True))
        context.report(p)
        if context.model is None or context.model.link(body) is None:
            raise PluginParameterError(f"gazebo_ros_p3d plugin error: bodyName: {body} does not exist")
        self.reference = None if self.frame in ("world", "/map", "map") else self.frame
        self.odometry = self.own(context.publisher(namespace, topic, Odometry))

    def update(self, now: float) -> None:
        if not self.rate.due(now):
            return
        from nav_msgs.msg import Odometry

        world = self.context.world
        state = world.link_state(self.link)
        pose = relative.carried_into_world(self.offset, state.pose)
        linear, angular = state.linear, state.angular
        if self.reference is not None:
            scoped = self.reference if "::" in self.reference else self.context.scoped(self.reference)
            frame = world.link_state(scoped)
            pose = relative.seen_from(pose, frame.pose)
            linear = relative.velocity_seen_from(linear, frame.linear, frame.pose)
            angular = relative.velocity_seen_from(angular, frame.angular, frame.pose)
        rng = world.rng
        jitter = rng.normal(0.0, self.noise, 9) if self.noise > 0 else np.zeros(9)
        msg = Odometry()
        msg.header.stamp = stamp(now)
        msg.header.frame_id = self.frame.lstrip("/")
        msg.child_frame_id = self.child_frame
        (msg.pose.pose.position.x, msg.pose.pose.position.y,
         msg.pose.pose.position.z) = (float(v + e) for v, e in zip(pose.position, jitter[:3], strict=True))
        (msg.pose.pose.orientation.x, msg.pose.pose.orientation.y, msg.pose.pose.orientation.z,
         msg.pose.pose.orientation.w) = pose.orientation
        (msg.twist.twist.linear.x, msg.twist.twist.linear.y,
         msg.twist.twist.linear.z) = (float(v + e) for v, e in zip(linear, jitter[3:6], strict=True))
        (msg.twist.twist.angular.x, msg.twist.twist.angular.y,
         msg.twist.twist.angular.z) = (float(v + e) for v, e in zip(angular, jitter[6:], strict=True))
        variance = self.noise * self.noise
        msg.pose.covariance = [variance if i % 7 == 0 else 0.0 for i in range(36)]
        msg.twist.covariance = [variance if i % 7 == 0 else 0.0 for i in range(36)]
        self.odometry.publish(msg)


class Bumper(GazeboPlugin):
    """libgazebo_ros_bumper.so: a contact sensor's contacts as gazebo_msgs/ContactsState."""

    def __init__(self, context: PluginContext) -> None:
        from gazebo_msgs.msg import ContactsState

        super().__init__(context)
        sensor = context.sensor()
        if sensor is None or sensor.type != "contact":
            raise PluginParameterError("bumper plugin must sit in a contact sensor (<sensor type=\"contact\">)")
        self.sensor = sensor
        self.link = context.scoped(context.plugin.link)
        contact = sensor.element.child("contact")
        # the collisions the sensor names, as SDF writes them or as Gazebo renames a URDF's lumped ones
        self.collisions = {c.text.strip() for c in contact.each("collision")} if contact is not None else set()
        p = context.parameters("bumper", "bumper plugin missing <{tag}>, defaults to {default}")
        namespace = context.namespace(p)
        topic = p.text("bumperTopicName", "bumper_states")
        self.frame = p.text("frameName", "world")
        self.rate = Every(sensor.update_rate)
        context.report(p)
        self.states = self.own(context.publisher(namespace, topic, ContactsState))

    def update(self, now: float) -> None:
        if not self.rate.due(now) or (not self.sensor.always_on and self.states.get_num_connections() == 0):
            return
        from gazebo_msgs.msg import ContactsState, ContactState
        from geometry_msgs.msg import Vector3, Wrench

        msg = ContactsState()
        msg.header.stamp = stamp(now)
        msg.header.frame_id = self.frame.lstrip("/")
        world = self.context.world
        for found in world.contacts(self.link):
            # the collisions named as Gazebo's contact messages name them (a URDF's lumped links)
            contact = replace(found, collision1=world.gazebo_collision_name(found.collision1),
                              collision2=world.gazebo_collision_name(found.collision2))
            mine = {found.collision1.rpartition("::")[2], contact.collision1.rpartition("::")[2]}
            if self.collisions and not mine & self.collisions:
                continue
            wrench = Wrench(Vector3(*contact.force), Vector3())
            msg.states.append(ContactState(
                info=f"Debug:  i:(0/1)     my geom:{contact.collision1}   other geom:{contact.collision2}"
                     f"         time:{now:.6f}\n",
                collision1_name=contact.collision1, collision2_name=contact.collision2, wrenches=[wrench],
                total_wrench=wrench, contact_positions=[Vector3(*contact.position)],
                contact_normals=[Vector3(*contact.normal)], depths=[contact.depth]))
        self.states.publish(msg)


class JointStatePublisher(GazeboPlugin):
    """libgazebo_ros_joint_state_publisher.so: the positions and velocities of <jointName>'s joints."""

    def __init__(self, context: PluginContext) -> None:
        from sensor_msgs.msg import JointState

        super().__init__(context)
        p = context.parameters("joint_state_publisher",
                               "GazeboRosJointStatePublisher Plugin missing <{tag}>, defaults to {default}")
        namespace = context.namespace(p)
        names = [n.strip() for n in p.text("jointName", "").split(",") if n.strip()]
        self.rate = Every(p.number("updateRate", 100.0))
        context.report(p)
        joints = {j.name for j in context.model.joints} if context.model is not None else set()
        missing = [n for n in names if n not in joints]
        if missing:
            raise PluginParameterError(f"GazeboRosJointStatePublisher: no joint named {', '.join(missing)} "
                                       f"in model [{context.model_name()}]")
        self.joints = names
        self.fixed = {j.name for j in context.model.joints if j.type == "fixed"} if context.model is not None else set()
        self.publisher = self.own(context.publisher(namespace, "joint_states", JointState))
        context.info(f"Starting GazeboRosJointStatePublisher Plugin (ns = {namespace})!, "
                     f"parent name: {context.model_name()}")

    def update(self, now: float) -> None:
        if not self.rate.due(now):
            return
        from sensor_msgs.msg import JointState

        world = self.context.world
        msg = JointState()
        msg.header.stamp = stamp(now)
        msg.name = list(self.joints)
        for joint in self.joints:
            if joint in self.fixed:  # a fixed joint has no state in the world: it stays at 0
                msg.position.append(0.0)
                msg.velocity.append(0.0)
                continue
            state = world.joint_state(self.context.scoped(joint))
            msg.position.append(state.position[0] if state.position else math.nan)
            msg.velocity.append(state.velocity[0] if state.velocity else math.nan)
        self.publisher.publish(msg)
