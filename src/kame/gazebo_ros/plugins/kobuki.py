"""The Kobuki's plugin, libgazebo_ros_kobuki.so (kobuki_gazebo_plugins): the TurtleBot's base as
its driver presents it. Its topics are under the model's name (spawned as mobile_base):
commands/velocity, commands/motor_power (kobuki_msgs/MotorPower: off releases the wheels) and
commands/reset_odometry (std_msgs/Empty) in; events/bumper (kobuki_msgs/BumperEvent), events/cliff
(kobuki_msgs/CliffEvent) and sensors/imu_data (sensor_msgs/Imu) out; odom, the odom ->
base_footprint transform and the wheels' joint_states at the top level, odometry from the wheel
encoders, and a stop when no command came for velocity_command_timeout seconds.

The events are changes of state, one message a sensor, as the robot sends them:
- a cliff sensor (a downward ray sensor named by cliff_sensor_{left,center,right}_name) is over a
  cliff when its first ray reads cliff_detection_threshold or more (nothing in range counts);
  `bottom` is that reading in millimetres (the ray's max range when it sees nothing): the real
  sensor's ADC value, which kobuki_gazebo_plugins approximates from the range, is not modelled.
- the bumper (the contact sensor named by bumper_name) is pressed where one of its link's contacts
  is 0.015-0.085 m above the robot's base, left from 30 to 90 degrees of the heading, centre within
  30 degrees of it, right from -30 to -90 degrees.
The IMU (the sensor named by imu_name) is read at the plugin's rate: orientation, rates and
accelerations in its link's frame, stamped with that link's name, with the Kobuki's covariances
(roll and pitch unknown: 1e6; yaw 0.05).
"""

from __future__ import annotations

import math
import threading
from typing import Any

from kame.gazebo_ros.conversions import stamp
from kame.gazebo_ros.plugins.base import PluginContext
from kame.gazebo_ros.plugins.drives import KOBUKI_MISSING, TwoWheelDrive, yaw_of
from kame.gazebo_ros.plugins.parameters import PluginParameterError

BUMPER_HEIGHT = (0.015, 0.085)  # metres above the base: the bumper ring, not the casters on the floor
SIDE = math.pi / 6  # the centre bumper's half-width


def cliff_bottom(distance: float, range_max: float) -> int:
    """A cliff event's `bottom` (uint16): the distance to the floor in millimetres."""
    return min(round(1000 * min(distance, range_max)), 65535)


def bumpers_pressed(contacts: list[Any], heading: float, base_height: float) -> set[int]:
    """LEFT (0), CENTER (1), RIGHT (2) pressed by contacts (positions and normals, from the robot
    outward, in the world)."""
    pressed: set[int] = set()
    for contact in contacts:
        if not BUMPER_HEIGHT[0] <= contact.position[2] - base_height <= BUMPER_HEIGHT[1]:
            continue
        towards = math.atan2(contact.normal[1], contact.normal[0]) - heading
        towards = math.atan2(math.sin(towards), math.cos(towards))
        if SIDE < towards <= math.pi / 2:
            pressed.add(0)
        elif -SIDE <= towards <= SIDE:
            pressed.add(1)
        elif -math.pi / 2 <= towards < -SIDE:
            pressed.add(2)
    return pressed


class Kobuki(TwoWheelDrive):
    """libgazebo_ros_kobuki.so."""

    def __init__(self, context: PluginContext) -> None:
        from kobuki_msgs.msg import BumperEvent, CliffEvent, MotorPower
        from sensor_msgs.msg import Imu
        from std_msgs.msg import Empty

        super().__init__(context)
        self.info = "GazeboRosKobuki"
        p = context.parameters(self.info, KOBUKI_MISSING)
        self.left = [p.text("left_wheel_joint_name", "wheel_left_joint")]
        self.right = [p.text("right_wheel_joint_name", "wheel_right_joint")]
        self.separation = p.number("wheel_separation", 0.23)
        self.diameter = p.number("wheel_diameter", 0.07)
        self.torque = p.number("torque", 1.0)
        self.timeout = p.number("velocity_command_timeout", 0.6)
        publish_tf = p.flag("publish_tf", True)
        self.cliff_threshold = p.number("cliff_detection_threshold", 0.04)
        cliff_names = [p.text(f"cliff_sensor_{side}_name", "", quiet=True) for side in ("left", "center", "right")]
        bumper_name = p.text("bumper_name", "", quiet=True)
        imu_name = p.text("imu_name", "", quiet=True)
        self.acceleration = 0.0
        self.legacy = False
        self.encoder = True
        self.publish_wheel_joint_state = True
        if self.diameter <= 0 or self.separation <= 0:
            raise PluginParameterError(f"{self.info}: <wheel_diameter> and <wheel_separation> must be above 0")
        context.report(p)
        self.cliffs = [self._sensor(name, "ray", f"{side} cliff sensor")
                       for name, side in zip(cliff_names, ("left", "center", "right"), strict=True)]
        self.bumper = self._sensor(bumper_name, "contact", "bumper")
        self.imu_sensor = self._sensor(imu_name, "imu", "IMU")
        self.over_cliff = [False, False, False]
        self.pressed: set[int] = set()
        self._motors_on = threading.Event()
        self._motors_on.set()
        self._reset_odometry = threading.Event()
        model = context.model_name()
        # the plugin's private NodeHandle is the model's name; odom and joint_states are global
        self._start_two_wheels("", f"/{model}/commands/velocity", 50.0, "odom", "odom", "base_footprint", publish_tf)
        self.cliff_events = self.own(context.publisher("", f"/{model}/events/cliff", CliffEvent))
        self.bumper_events = self.own(context.publisher("", f"/{model}/events/bumper", BumperEvent))
        self.imu = self.own(context.publisher("", f"/{model}/sensors/imu_data", Imu))
        self.own(context.subscriber("", f"/{model}/commands/motor_power", MotorPower, self._on_motor_power))
        self.own(context.subscriber("", f"/{model}/commands/reset_odometry", Empty,
                                    lambda _msg: self._reset_odometry.set()))

    def _sensor(self, name: str, kind: str, what: str) -> Any:
        """The World's SensorInfo of the model's sensor called `name`, as the plugin finds it by name."""
        model = self.context.model_name()
        found = next((s for s in self.context.world.sensors() if s.model == model and s.name == name), None)
        if found is None or found.type != kind:
            raise PluginParameterError(f"{self.info}: Couldn't find the {what} [{name}] in the model!")
        return found

    def _on_motor_power(self, msg: Any) -> None:
        """On a subscriber's thread: only flags, which the stepping thread reads."""
        if msg.state == 1:
            self._motors_on.set()
        elif msg.state == 0:
            self._motors_on.clear()

    def update(self, now: float) -> None:
        if not self.rate.due(now):
            return
        if self._reset_odometry.is_set():
            self._reset_odometry.clear()
            self.reset_encoders()
        if not self._motors_on.is_set():
            self.command.stop()
        self.step_wheels(now)
        self._publish_imu(now)
        self._cliff_events()
        self._bumper_events()

    def _publish_imu(self, now: float) -> None:
        from sensor_msgs.msg import Imu

        reading = self.context.world.imu_reading(self.imu_sensor)
        msg = Imu()
        msg.header.stamp = stamp(now)
        msg.header.frame_id = self.imu_sensor.link.rpartition("::")[2]
        msg.orientation.x, msg.orientation.y, msg.orientation.z, msg.orientation.w = reading.orientation
        msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z = reading.angular_velocity
        (msg.linear_acceleration.x, msg.linear_acceleration.y,
         msg.linear_acceleration.z) = reading.linear_acceleration
        kobuki = [1e6, 0.0, 0.0, 0.0, 1e6, 0.0, 0.0, 0.0, 0.05]
        msg.orientation_covariance = kobuki
        msg.angular_velocity_covariance = list(kobuki)
        self.imu.publish(msg)

    def _cliff_events(self) -> None:
        from kobuki_msgs.msg import CliffEvent

        world = self.context.world
        for index, sensor in enumerate(self.cliffs):
            scan = world.ray_scan(sensor)
            distance = float(scan.ranges[0][0])
            cliff = distance >= self.cliff_threshold
            if cliff != self.over_cliff[index]:
                self.over_cliff[index] = cliff
                bottom = cliff_bottom(distance, scan.config.range_max)
                self.cliff_events.publish(CliffEvent(sensor=index, state=int(cliff), bottom=bottom))

    def _bumper_events(self) -> None:
        from kobuki_msgs.msg import BumperEvent

        world = self.context.world
        base = world.model_state(self.context.model_name()).pose
        pressed = bumpers_pressed(world.contacts(self.bumper.link), yaw_of(base), base.position[2])
        for bumper in sorted(pressed ^ self.pressed):
            self.bumper_events.publish(BumperEvent(bumper=bumper, state=int(bumper in pressed)))
        self.pressed = pressed

    def reset(self) -> None:
        super().reset()
        self.over_cliff = [False, False, False]
        self.pressed = set()
