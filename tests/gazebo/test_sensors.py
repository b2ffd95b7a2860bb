"""Sensors against geometry: laser ranges to known walls, a range sensor reading its wall, a camera
seeing a red box at the pixels its K predicts, depth equal to distances, an IMU at rest, a bumper."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from tests.gazebo import in_own_process, require_engine

require_engine()

from kame.gazebo import Pose, SensorInfo, State, World  # noqa: E402  (MuJoCo loads once require_engine has checked it can)
from kame.gazebo.camera import optical_points  # noqa: E402  (MuJoCo loads once require_engine has checked it can)

WALLS = """<model name="walls"><static>true</static><link name="link">
  <collision name="east"><pose>3 0 1 0 0 0</pose><geometry><box><size>0.2 30 2</size></box></geometry></collision>
  <collision name="north"><pose>0 2 1 0 0 0</pose><geometry><box><size>30 0.2 2</size></box></geometry></collision>
  <visual name="east"><pose>3 0 1 0 0 0</pose><geometry><box><size>0.2 30 2</size></box></geometry></visual>
</link></model>"""


def laser(noise: str = "", samples: int = 181, vertical: str = "") -> str:
    return f"""<model name="robot"><static>true</static><pose>0 0 0.5 0 0 0</pose><link name="base">
      <collision name="body"><geometry><cylinder><radius>0.2</radius><length>0.2</length></cylinder></geometry>
      </collision>
      <sensor name="laser" type="ray"><pose>0 0 0.1 0 0 0</pose><update_rate>10</update_rate>
        <ray><scan><horizontal><samples>{samples}</samples><resolution>1</resolution>
          <min_angle>-1.5707963</min_angle><max_angle>1.5707963</max_angle></horizontal>{vertical}</scan>
          <range><min>0.1</min><max>10</max><resolution>0.01</resolution></range>{noise}</ray>
        <plugin name="laser_plugin" filename="libgazebo_ros_laser.so"><topicName>/scan</topicName>
          <frameName>base_laser</frameName></plugin>
      </sensor></link></model>"""


def world_with(*models: str) -> World:
    return World.from_sdf(f'<sdf version="1.6"><world name="w">{"".join(models)}</world></sdf>')


def only_sensor(world: World, name: str) -> SensorInfo:
    return next(s for s in world.sensors() if s.name == name)


def test_laser_ranges_reach_the_walls_within_a_centimetre() -> None:
    world = world_with(WALLS, laser())
    sensor = only_sensor(world, "laser")
    assert (sensor.model, sensor.link, sensor.type, sensor.update_rate) == ("robot", "robot::base", "ray", 10.0)
    scan = world.ray_scan(sensor)
    assert scan.ranges.shape == (1, 181)
    angles = scan.horizontal_angles
    # the east wall's face is at x = 2.9, the north wall's at y = 1.9; rays within the cylinder's
    # own link are not seen (the sensor's link is excluded)
    expected = np.minimum(np.where(np.cos(angles) > 1e-9, 2.9 / np.maximum(np.cos(angles), 1e-9), np.inf),
                          np.where(np.sin(angles) > 1e-9, 1.9 / np.maximum(np.sin(angles), 1e-9), np.inf))
    expected[expected > 10] = np.inf
    finite = np.isfinite(expected)
    assert np.array_equal(np.isfinite(scan.ranges[0]), finite)
    assert np.abs(scan.ranges[0][finite] - expected[finite]).max() < 0.01
    world.close()


def test_rays_skip_the_links_welded_to_the_sensors_but_see_other_models() -> None:
    # a Kobuki's cliff sensor: a link on a fixed joint inside the base's collision, looking down.
    # Gazebo lumps the two links into one, whose collisions its rays skip: the ray reads the floor
    base = """<model name="base"><pose>0 0 0 0 0 0</pose><link name="base_link"><pose>0 0 0.1 0 0 0</pose>
      <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
      <collision name="body"><geometry><box><size>0.4 0.4 0.1</size></box></geometry></collision></link>
      <link name="cliff_link"><pose>0.1 0 0.1 0 1.5707963 0</pose>
      <inertial><mass>0.001</mass><inertia><ixx>1e-6</ixx><iyy>1e-6</iyy><izz>1e-6</izz></inertia></inertial>
      <sensor name="cliff" type="ray"><ray><scan><horizontal><samples>3</samples><min_angle>-0.04</min_angle>
        <max_angle>0.04</max_angle></horizontal></scan><range><min>0.01</min><max>1</max></range></ray></sensor></link>
      <joint name="cliff_joint" type="fixed"><parent>base_link</parent><child>cliff_link</child></joint></model>"""
    floor = """<model name="floor"><static>true</static><link name="link"><collision name="c">
      <pose>0 0 -0.05 0 0 0</pose><geometry><box><size>5 5 0.1</size></box></geometry></collision></link></model>"""
    world = world_with(floor, base)
    ranges = world.ray_scan(only_sensor(world, "cliff")).ranges[0]
    assert ranges[1] == pytest.approx(0.1, abs=1e-6)  # the floor, not the base's underside 0.05 below
    assert np.allclose(ranges, 0.1 / np.cos(np.array([-0.04, 0.0, 0.04])), atol=1e-6)
    world.close()


def test_laser_noise_is_gaussian_with_its_mean_and_stddev_and_replays() -> None:
    noise = "<noise><type>gaussian</type><mean>0.05</mean><stddev>0.02</stddev></noise>"
    ranges = []
    for _ in range(2):
        world = world_with(WALLS, laser(noise, samples=2001))
        scan = world.ray_scan(only_sensor(world, "laser"))
        ranges.append(scan.ranges[0])
    east = np.abs(world.ray_scan(only_sensor(world, "laser")).horizontal_angles) < 0.3
    errors = ranges[0][east] - 2.9 / np.cos(np.linspace(-math.pi / 2, math.pi / 2, 2001)[east])
    assert errors.mean() == pytest.approx(0.05, abs=0.005)
    assert errors.std() == pytest.approx(0.02, abs=0.004)
    assert np.array_equal(ranges[0], ranges[1])  # the world's seeded generator: runs replay


def test_vertical_samples_scan_a_plane_of_rays() -> None:
    vertical = "<vertical><samples>3</samples><min_angle>-0.2</min_angle><max_angle>0.2</max_angle></vertical>"
    world = world_with(WALLS, laser(vertical=vertical, samples=5))
    scan = world.ray_scan(only_sensor(world, "laser"))
    assert scan.ranges.shape == (3, 5)
    middle = scan.ranges[:, 2]  # straight ahead at each elevation: 2.9 / cos(elevation)
    assert middle == pytest.approx(2.9 / np.cos(np.array([-0.2, 0.0, 0.2])), abs=0.01)


RANGE_WORLD = """<model name="sonar_box"><static>true</static><pose>0 0 0.5 0 0 0</pose><link name="link">
  <sensor name="sonar" type="ray"><update_rate>50</update_rate><ray><scan>
    <horizontal><samples>10</samples><resolution>1</resolution><min_angle>-0.1</min_angle><max_angle>0.1</max_angle>
    </horizontal><vertical><samples>10</samples><resolution>1</resolution><min_angle>-0.1</min_angle>
    <max_angle>0.1</max_angle></vertical></scan><range><min>0.02</min><max>4</max></range></ray>
    <plugin name="gazebo_ros_range" filename="libgazebo_ros_range.so"><radiation>ultrasound</radiation>
      <fov>0.2</fov></plugin></sensor>
  <sensor name="true_sonar" type="sonar"><sonar><min>0.02</min><max>4</max><radius>0.3</radius></sonar></sensor>
</link></model>"""


def test_a_range_sensor_reads_its_wall() -> None:
    world = world_with(WALLS, RANGE_WORLD)
    reading = world.range_reading(only_sensor(world, "sonar"))
    assert reading.range == pytest.approx(2.9, abs=0.01)
    assert (reading.min_range, reading.max_range) == (0.02, 4.0)
    assert reading.field_of_view == pytest.approx(0.2)
    sonar = world.range_reading(only_sensor(world, "true_sonar"))
    assert sonar.range == pytest.approx(2.9, abs=0.01) and sonar.field_of_view == pytest.approx(2 * math.atan(0.3 / 4))
    world.set_model_state("sonar_box", State(Pose((0.0, 0.0, 0.5), (0.0, 0.0, 1.0, 0.0))))
    assert world.range_reading(only_sensor(world, "sonar")).range == math.inf  # facing west: nothing within 4 m


def camera(width: int = 320, height: int = 240, fov: float = 1.2, kind: str = "camera") -> str:
    return f"""<model name="eye"><static>true</static><pose>0 0 0.5 0 0 0</pose><link name="link">
      <sensor name="cam" type="{kind}"><update_rate>30</update_rate><camera><horizontal_fov>{fov}</horizontal_fov>
        <image><width>{width}</width><height>{height}</height><format>R8G8B8</format></image>
        <clip><near>0.05</near><far>20</far></clip></camera></sensor></link></model>"""


def red_box(x: float, y: float, z: float, size: float = 0.2) -> str:
    geometry = f"<geometry><box><size>{size} {size} {size}</size></box></geometry>"
    return f"""<model name="red_box"><static>true</static><pose>{x} {y} {z} 0 0 0</pose><link name="link">
      <collision name="c">{geometry}</collision><visual name="v">{geometry}
      <material><script><name>Gazebo/Red</name></script></material></visual></link></model>"""


@pytest.mark.usefixtures("renders")
@in_own_process
def test_a_camera_sees_a_red_box_at_the_pixels_its_k_predicts() -> None:
    world = world_with(red_box(3.0, 0.6, 0.8), camera())
    frame = world.camera_frame(only_sensor(world, "cam"))
    assert frame.rgb is not None and frame.rgb.shape == (240, 320, 3) and frame.rgb.dtype == np.uint8
    fx, _, cx, _, fy, cy, *_ = frame.config.k()

    def pixel(x: float, y: float, z: float) -> tuple[float, float]:  # optical frame: right -y, down -z, forward x
        return cx + fx * -y / x, cy + fy * -(z - 0.5) / x

    rgb = frame.rgb.astype(int)
    red = (rgb[:, :, 0] > 60) & (rgb[:, :, 0] > 2 * rgb[:, :, 1]) & (rgb[:, :, 0] > 2 * rgb[:, :, 2])
    rows, cols = np.nonzero(red)
    assert len(rows) > 50
    # a box is convex: its outline's outermost pixels are its corners' projections (the camera, below
    # and right of it, sees its near face, its right side and its bottom, all red in the ambient light)
    corners = [pixel(x, y, z) for x in (2.9, 3.1) for y in (0.5, 0.7) for z in (0.7, 0.9)]
    us, vs = [u for u, _ in corners], [v for _, v in corners]
    assert (cols.min(), cols.max()) == (pytest.approx(min(us), abs=1.0), pytest.approx(max(us), abs=1.0))
    assert (rows.min(), rows.max()) == (pytest.approx(min(vs), abs=1.0), pytest.approx(max(vs), abs=1.0))
    # elsewhere the scene's background: Gazebo's default grey
    assert tuple(frame.rgb[5, 5]) == (178, 178, 178)
    world.close()


@pytest.mark.usefixtures("renders")
@in_own_process
def test_depth_values_equal_distances_along_the_optical_axis() -> None:
    world = world_with(WALLS, camera(160, 120, 1.0, "depth"))
    sensor = only_sensor(world, "cam")
    frame = world.camera_frame(sensor, rgb=False, depth=True)
    assert frame.rgb is None and frame.depth is not None and frame.depth.shape == (120, 160)
    # the east wall's face at x = 2.9 is 2.9 m deep at every pixel that sees it
    assert frame.depth[60, 80] == pytest.approx(2.9, abs=0.01)
    assert frame.depth[60, 10] == pytest.approx(2.9, abs=0.01)
    points = optical_points(frame.depth, frame.config)
    metres_a_pixel = 2.9 / frame.config.focal_length()  # on the wall
    # pixel (80, 60) is half a pixel right of and below the optical axis (cx = 79.5, cy = 59.5)
    assert points[60, 80] == pytest.approx((0.5 * metres_a_pixel, 0.5 * metres_a_pixel, 2.9), abs=0.01)
    assert points[60, 10] == pytest.approx((-69.5 * metres_a_pixel, 0.5 * metres_a_pixel, 2.9), abs=0.01)
    # looking west, nothing within the far clip: +inf
    world.set_model_state("eye", State(Pose((0.0, 0.0, 0.5), (0.0, 0.0, 1.0, 0.0))))
    west = world.camera_frame(sensor, rgb=False, depth=True).depth
    assert west is not None and np.isinf(west).all()
    world.close()


IMU = """<model name="imu_box"><pose>0 0 0.1 0 0 0.5</pose><link name="link">
  <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
  <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>
  <sensor name="imu" type="imu"><update_rate>100</update_rate></sensor></link></model>"""


def test_an_imu_at_rest_feels_gravity_upward_and_reads_its_heading() -> None:
    world = world_with("<include><uri>model://ground_plane</uri></include>", IMU)
    world.step(500)
    reading = world.imu_reading(only_sensor(world, "imu"))
    assert reading.linear_acceleration == pytest.approx((0.0, 0.0, 9.8), abs=0.02)
    assert reading.angular_velocity == pytest.approx((0.0, 0.0, 0.0), abs=1e-3)
    assert reading.orientation == pytest.approx((0.0, 0.0, math.sin(0.25), math.cos(0.25)), abs=1e-3)


def test_a_links_acceleration_is_what_an_accelerometer_feels() -> None:
    world = world_with("<include><uri>model://ground_plane</uri></include>", IMU)
    world.step(500)
    linear, angular = world.link_acceleration("imu_box::link")
    assert linear == pytest.approx((0.0, 0.0, 9.8), abs=0.02) and angular == pytest.approx((0.0, 0.0, 0.0), abs=0.01)
    falling = world_with(IMU.replace("0 0 0.1 0 0 0.5", "0 0 5 0 0 0.5"))
    falling.step(10)
    assert falling.link_acceleration("imu_box::link")[0] == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)  # free fall


def test_imu_noise_per_axis_has_its_mean_and_stddev() -> None:
    noise = "".join(f"<{axis}><noise type='gaussian'><mean>0.1</mean><stddev>0.05</stddev></noise></{axis}>"
                    for axis in "xyz")
    world = world_with("<include><uri>model://ground_plane</uri></include>", IMU.replace(
        "<update_rate>100</update_rate>", f"<update_rate>100</update_rate><imu><angular_velocity>{noise}"
                                          "</angular_velocity></imu>"))
    world.step(500)
    sensor = only_sensor(world, "imu")
    readings = np.array([world.imu_reading(sensor).angular_velocity for _ in range(2000)])
    assert readings.mean(axis=0) == pytest.approx((0.1, 0.1, 0.1), abs=0.005)
    assert readings.std(axis=0) == pytest.approx((0.05, 0.05, 0.05), abs=0.005)
    assert world.imu_reading(sensor).linear_acceleration == pytest.approx((0.0, 0.0, 9.8), abs=0.02)  # no noise


def test_a_bumper_reports_its_links_contacts_and_the_force() -> None:
    world = world_with("<include><uri>model://ground_plane</uri></include>", IMU)
    world.step(500)
    found = world.contacts("imu_box::link")
    assert found and {c.collision1 for c in found} == {"imu_box::link::c"}
    assert {c.collision2 for c in found} == {"ground_plane::link::collision"}
    assert sum(c.force[2] for c in found) == pytest.approx(9.8, rel=0.01)  # the ground holds the box up
    assert all(c.normal[2] < -0.99 for c in found)  # from the box's collision outward: down into the ground
    assert world.contacts("ground_plane::link")[0].collision1 == "ground_plane::link::collision"


def sonar_cube(name: str, x: float) -> str:
    """A 5 cm cube carrying a ray sensor 25 cm ahead of its centre, as gazebo_ros_range.world's models do."""
    cube = "<geometry><box><size>0.05 0.05 0.05</size></box></geometry>"
    axis = "<samples>5</samples><resolution>1</resolution><min_angle>-0.25</min_angle><max_angle>0.25</max_angle>"
    return f"""<model name="{name}"><pose>{x} 0 0 0 0 0</pose><link name="link"><gravity>false</gravity>
      <visual name="v">{cube}</visual><collision name="c">{cube}</collision>
      <sensor type="ray" name="sonar"><pose>0.25 0 0 0 0 0</pose><update_rate>5</update_rate><ray><scan>
        <horizontal>{axis}</horizontal><vertical>{axis}</vertical></scan>
        <range><min>0.01</min><max>0.75</max><resolution>0.01</resolution></range></ray>
        <plugin filename="libgazebo_ros_range.so" name="range"><fov>0.5</fov><radiation>ultrasound</radiation>
        </plugin></sensor></link></model>"""


def test_two_sonar_cubes_in_an_sdf_1_4_world_without_gravity() -> None:
    world = World.from_sdf(f"""<sdf version="1.4"><world name="range"><physics type="ode">
      <gravity>0 0 0</gravity><max_step_size>0.001</max_step_size></physics>
      {sonar_cube("first", 0.0)}{sonar_cube("second", 0.5)}
      <light type="point" name="lamp"><pose>0 0 10 0 0 0</pose><spot><inner_angle>1.57</inner_angle></spot></light>
      </world></sdf>""")
    assert world.physics.gravity == (0.0, 0.0, 0.0)
    world.step(200)
    first, second = (s for s in world.sensors() if s.name == "sonar")
    # the second cube's near face is at x = 0.475, the first sonar at x = 0.25: 0.225 m; nothing before the second
    assert world.range_reading(first).range == pytest.approx(0.225, abs=0.005)
    assert world.range_reading(second).range == math.inf
    assert world.model_state("second").pose.position == pytest.approx((0.5, 0.0, 0.0))  # no gravity, no drift


def test_rays_see_a_collision_mesh_itself_not_its_hull(tmp_path: Path) -> None:
    import trimesh

    apart = [trimesh.creation.box((0.2, 0.2, 0.2)) for _ in range(2)]
    apart[0].apply_translation((0.0, 0.5, 0.0))
    apart[1].apply_translation((0.0, -0.5, 0.0))
    (apart[0] + apart[1]).export(str(tmp_path / "two.stl"))
    eye = """<model name="eye"><static>true</static><link name="l"><sensor name="s" type="ray"><ray><scan><horizontal>
      <samples>3</samples><min_angle>-0.2449787</min_angle><max_angle>0.2449787</max_angle></horizontal></scan>
      <range><min>0.05</min><max>10</max></range></ray></sensor></link></model>"""
    world = world_with(f"""<model name="m"><static>true</static><pose>2 0 0 0 0 0</pose><link name="l">
      <collision name="c"><geometry><mesh><uri>{tmp_path}/two.stl</uri></mesh></geometry></collision></link></model>""",
                       eye)
    ranges = world.ray_scan(only_sensor(world, "s")).ranges[0]
    assert ranges[1] == math.inf  # straight between the boxes
    assert ranges[0] == pytest.approx(1.9 / math.cos(0.2449787), abs=0.01)  # at the boxes' near faces


@pytest.mark.usefixtures("renders")
@in_own_process
def test_camera_noise_is_gaussian_in_intensity() -> None:
    noisy = camera().replace("<clip>", "<noise><type>gaussian</type><mean>0</mean><stddev>0.05</stddev></noise><clip>")
    clean_world, noisy_world = world_with(red_box(3.0, 0.6, 0.8), camera()), world_with(red_box(3.0, 0.6, 0.8), noisy)
    clean = clean_world.camera_frame(only_sensor(clean_world, "cam")).rgb
    grainy = noisy_world.camera_frame(only_sensor(noisy_world, "cam")).rgb
    assert clean is not None and grainy is not None
    face = (slice(90, 100), slice(106, 117))  # inside the red face, far from 0 and 255
    difference = grainy[face].astype(float) - clean[face].astype(float)
    assert difference.mean() == pytest.approx(0.0, abs=1.5) and difference.std() == pytest.approx(0.05 * 255, rel=0.15)
    clean_world.close()
    noisy_world.close()


@pytest.mark.usefixtures("renders")
@in_own_process
def test_a_camera_sees_the_scenes_background() -> None:
    world = World.from_sdf(f"""<sdf version="1.6"><world name="w"><scene><ambient>0.1 0.2 0.3 1</ambient>
      <background>0 0 1 1</background></scene>{camera(32, 24)}</world></sdf>""")
    assert world.scene.ambient == (0.1, 0.2, 0.3, 1.0) and world.scene.background == (0.0, 0.0, 1.0, 1.0)
    frame = world.camera_frame(only_sensor(world, "cam"), depth=True)
    assert frame.rgb is not None and (frame.rgb == (0, 0, 255)).all()
    assert frame.depth is not None and np.isinf(frame.depth).all()
    world.close()
