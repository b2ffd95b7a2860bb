"""The world's physics against closed forms: free fall, a pendulum's period, a box sliding to a
stop with friction (and with <mu2> apart from <mu>), a two-wheeled body driven along an arc, and
a joint's <velocity> limit against applied efforts and drives."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from tests.gazebo import require_engine

require_engine()

from kame.gazebo import State, World  # noqa: E402  (MuJoCo loads once require_engine has checked it can)

G = 9.8


def sdf_world(body: str, physics: str = "") -> str:
    return f'<sdf version="1.6"><world name="test">{physics}{body}</world></sdf>'


GROUND = "<include><uri>model://ground_plane</uri></include>"


def ball(name: str = "ball", z: float = 10.0, mu: float = 1.0, extra: str = "") -> str:
    return f"""<model name="{name}"><pose>0 0 {z} 0 0 0</pose><link name="link">
      <inertial><mass>1</mass><inertia><ixx>0.004</ixx><iyy>0.004</iyy><izz>0.004</izz></inertia></inertial>
      <collision name="collision"><geometry><sphere><radius>0.1</radius></sphere></geometry>
        <surface><friction><ode><mu>{mu}</mu><mu2>{mu}</mu2></ode></friction></surface></collision>
      <visual name="visual"><geometry><sphere><radius>0.1</radius></sphere></geometry></visual>{extra}
    </link></model>"""


def test_free_fall_follows_z_of_t_within_one_percent() -> None:
    world = World.from_sdf(sdf_world(ball(z=10.0)))
    for t in (0.25, 0.5, 1.0):
        world.step(round((t - world.sim_time) / world.physics.max_step_size))
        drop = 10.0 - world.model_state("ball").pose.position[2]
        assert drop == pytest.approx(0.5 * G * t * t, rel=0.01)
        assert world.model_state("ball").linear[2] == pytest.approx(-G * t, rel=0.01)
    assert world.iterations == 1000 and world.sim_time == pytest.approx(1.0)


def test_gravity_is_the_worlds_and_can_be_changed() -> None:
    world = World.from_sdf(sdf_world(ball(z=10.0), "<gravity>0 0 -1.62</gravity>"))
    assert world.physics.gravity == (0.0, 0.0, -1.62)
    world.step(1000)
    assert 10.0 - world.model_state("ball").pose.position[2] == pytest.approx(0.5 * 1.62, rel=0.01)
    world.physics = replace(world.physics, gravity=(0.0, 0.0, 0.0), max_step_size=0.002)
    height = world.model_state("ball").pose.position[2]
    speed = world.model_state("ball").linear[2]
    world.step(500)
    assert world.sim_time == pytest.approx(2.0)
    assert world.model_state("ball").pose.position[2] == pytest.approx(height + speed * 1.0, rel=1e-6)


def pendulum(length: float, angle: float) -> World:
    world = World.from_sdf(sdf_world(f"""<model name="pendulum"><link name="bob"><pose>0 0 {3 - length} 0 0 0</pose>
      <inertial><mass>1</mass><inertia><ixx>1e-6</ixx><iyy>1e-6</iyy><izz>1e-6</izz></inertia></inertial>
      <visual name="v"><geometry><sphere><radius>0.05</radius></sphere></geometry></visual></link>
      <joint name="hinge" type="revolute"><parent>world</parent><child>bob</child>
        <pose>0 0 {length} 0 0 0</pose><axis><xyz>0 1 0</xyz></axis></joint></model>"""))
    world.set_joint_positions("pendulum", {"hinge": angle})
    return world


def test_a_small_angle_pendulums_period_within_one_percent() -> None:
    length = 0.8
    world = pendulum(length, 0.05)
    crossings: list[float] = []
    before = world.joint_state("pendulum::hinge").position[0]
    while len(crossings) < 5:
        world.step()
        now = world.joint_state("pendulum::hinge").position[0]
        if (before > 0 >= now) or (before < 0 <= now):
            crossings.append(world.sim_time - world.physics.max_step_size * now / (now - before))
        before = now
    period = (crossings[4] - crossings[0]) / 2
    assert period == pytest.approx(2 * math.pi * math.sqrt(length / G), rel=0.01)


def slide(mu: float, mu2: float, speed: float) -> tuple[World, float]:
    """A 0.2 m box set sliding along x on the ground: the world, and how far it went."""
    box = f"""<model name="box"><pose>0 0 0.1 0 0 0</pose><link name="link">
      <inertial><mass>1</mass><inertia><ixx>0.0067</ixx><iyy>0.0067</iyy><izz>0.0067</izz></inertia></inertial>
      <collision name="collision"><geometry><box><size>0.2 0.2 0.2</size></box></geometry>
        <surface><friction><ode><mu>{mu}</mu><mu2>{mu2}</mu2></ode></friction></surface></collision></link></model>"""
    world = World.from_sdf(sdf_world(GROUND + box))
    world.step(200)  # settle on the ground
    start = world.model_state("box").pose
    world.set_model_state("box", State(start, (speed, 0.0, 0.0)))
    for _ in range(3000):
        world.step(10)
        if abs(world.model_state("box").linear[0]) < 1e-3:
            break
    return world, world.model_state("box").pose.position[0] - start.position[0]


def test_a_sliding_box_stops_at_v_squared_over_two_mu_g() -> None:
    mu, speed = 0.5, 2.0
    world, distance = slide(mu, mu, speed)
    # the ground plane's mu is 100 (mu2 50): the box's 0.5 is what counts, as ODE takes the smaller
    assert distance == pytest.approx(speed ** 2 / (2 * mu * G), rel=0.05)
    assert world.take_warnings() == []  # the ground plane's mu2 apart from its mu matters nowhere


def test_mu2_apart_from_mu_takes_the_smaller_and_says_so() -> None:
    # MuJoCo's friction is isotropic: the box grips as ODE's weaker direction would
    speed = 2.0
    for mu, mu2 in ((1.0, 0.25), (0.25, 1.0)):
        world, distance = slide(mu, mu2, speed)
        assert distance == pytest.approx(speed ** 2 / (2 * 0.25 * G), rel=0.05), (mu, mu2)
        warnings = world.take_warnings()
        assert len(warnings) == 1 and "'box'" in warnings[0] and "link::collision" in warnings[0], warnings
        assert "mu2" in warnings[0] and "smaller" in warnings[0]


def spinner(velocity_limit: float) -> World:
    """A disc on a vertical hinge (no gravity along it), its <limit><velocity> given."""
    return World.from_sdf(sdf_world(f"""<model name="spinner"><link name="disc"><pose>0 0 1 0 0 0</pose>
      <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
      <visual name="v"><geometry><cylinder><radius>0.1</radius><length>0.02</length></cylinder></geometry></visual>
      </link><joint name="hinge" type="revolute"><parent>world</parent><child>disc</child><axis><xyz>0 0 1</xyz>
      <limit><lower>-1e16</lower><upper>1e16</upper><velocity>{velocity_limit}</velocity></limit></axis></joint>
      </model>"""))


def test_a_joints_velocity_limit_holds_against_efforts_and_drives() -> None:
    world = spinner(2.0)
    world.apply_joint_effort("spinner::hinge", 1.0, None, 1.0)  # unlimited: 100 rad/s^2 for a second
    world.step(1000)
    speed = world.joint_state("spinner::hinge").velocity[0]
    assert 1.9 < speed < 2.0 + 100 * world.physics.max_step_size + 1e-9  # at most a step's push past it
    world.clear_joint_forces()
    world.apply_joint_effort("spinner::hinge", -1.0, None, 2.0)
    world.step(2000)
    assert -2.2 < world.joint_state("spinner::hinge").velocity[0] < -1.9  # the other way too
    world.clear_joint_forces()
    world.drive_joint("spinner::hinge", 10.0, 1.0)
    world.step(500)
    assert world.joint_state("spinner::hinge").velocity[0] == pytest.approx(2.0, abs=0.01)

    free = spinner(-1.0)  # below 0: no limit, as SDF's default
    free.apply_joint_effort("spinner::hinge", 1.0, None, 1.0)
    free.step(1000)
    assert free.joint_state("spinner::hinge").velocity[0] == pytest.approx(100.0, rel=0.01)


def two_wheeler(radius: float = 0.05, separation: float = 0.3) -> str:
    def wheel(side: str, y: float) -> str:
        return f"""<link name="{side}_wheel"><pose>0 {y} {radius} -1.5707963 0 0</pose>
          <inertial><mass>0.2</mass><inertia><ixx>1.5e-4</ixx><iyy>1.5e-4</iyy><izz>2.5e-4</izz></inertia></inertial>
          <collision name="collision"><geometry><cylinder><radius>{radius}</radius><length>0.02</length></cylinder>
          </geometry><surface><friction><ode><mu>1</mu><mu2>1</mu2></ode></friction></surface></collision></link>
          <joint name="{side}_wheel_joint" type="continuous"><parent>chassis</parent><child>{side}_wheel</child>
            <axis><xyz>0 0 1</xyz></axis></joint>"""

    def caster(name: str, x: float) -> str:
        return f"""<collision name="{name}"><pose>{x} 0 -0.038 0 0 0</pose><geometry><sphere><radius>0.025</radius>
          </sphere></geometry><surface><friction><ode><mu>0</mu><mu2>0</mu2></ode></friction></surface></collision>"""

    return f"""<model name="robot"><link name="chassis"><pose>0 0 {radius + 0.015} 0 0 0</pose>
      <inertial><mass>2</mass><inertia><ixx>0.01</ixx><iyy>0.02</iyy><izz>0.02</izz></inertia></inertial>
      <collision name="body"><geometry><box><size>0.3 0.2 0.04</size></box></geometry></collision>
      {caster("front_caster", 0.12)}{caster("back_caster", -0.12)}</link>
      {wheel("left", separation / 2)}{wheel("right", -separation / 2)}</model>"""


def test_wheel_velocities_drive_the_expected_arc() -> None:
    radius, separation = 0.05, 0.3
    world = World.from_sdf(sdf_world(GROUND + two_wheeler(radius, separation)))
    world.step(300)
    left, right = 4.0, 6.0  # rad/s
    world.drive_joint("robot::left_wheel_joint", left, 5.0)
    world.drive_joint("robot::right_wheel_joint", right, 5.0)
    world.step(200)  # up to speed
    start = world.model_state("robot").pose
    seconds = 3.0
    world.step(round(seconds / world.physics.max_step_size))
    linear, angular = radius * (left + right) / 2, radius * (right - left) / separation
    arc = linear / angular
    theta = angular * seconds
    expected = (arc * math.sin(theta), arc * (1 - math.cos(theta)))
    end = start.inverse() * world.model_state("robot").pose  # where it went, seen from where it was
    assert math.dist(end.position[:2], expected) < 0.02 * linear * seconds  # within 2 % of the way driven
    assert end.rpy()[2] == pytest.approx(theta, rel=0.02)
    assert world.model_state("robot").linear[2] == pytest.approx(0.0, abs=0.01)
    world.release_joint("robot::left_wheel_joint")
    world.release_joint("robot::right_wheel_joint")


def test_a_drive_is_limited_by_its_torque() -> None:
    world = World.from_sdf(sdf_world(GROUND + two_wheeler()))
    world.step(300)
    world.drive_joint("robot::left_wheel_joint", 100.0, 0.001)
    world.drive_joint("robot::right_wheel_joint", 100.0, 0.001)
    world.step(500)
    assert world.joint_state("robot::left_wheel_joint").velocity[0] < 10.0


def test_casters_of_mu_0_touching_the_ground_drive_the_arc_without_diverging() -> None:
    # the casters of a URDF robot sit on the ground with mu 0 (<gazebo reference><mu1>0</mu1>): a
    # degenerate friction cone in MuJoCo, which diverged within half a second of driving
    radius, separation = 0.05, 0.3
    wheeler = two_wheeler(radius, separation).replace("-0.038 0 0 0", "-0.04 0 0 0")
    world = World.from_sdf(sdf_world(GROUND + wheeler))
    world.step(300)
    world.drive_joint("robot::left_wheel_joint", 4.0, 5.0)
    world.drive_joint("robot::right_wheel_joint", 6.0, 5.0)
    world.step(3000)
    assert world.take_warnings() == []
    end = world.model_state("robot").pose
    assert end.rpy()[2] == pytest.approx(radius * 2.0 / separation * 2.8, rel=0.05)  # turned as driven
