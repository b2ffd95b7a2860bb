"""SDF and URDF features reaching the running world: includes on GAZEBO_MODEL_PATH, relative_to
poses, nested models, static models, joints with limits and damping, materials, meshes, lights,
plugins and sensors as the ROS side reads them, URDF with its <gazebo> tags, spawning and
deleting, wrenches and efforts, resets."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from tests.gazebo import in_own_process, require_engine

require_engine()

from kame.gazebo import SHIPPED_MODELS, GazeboError, Physics, Pose, Resources, State, World  # noqa: E402  (MuJoCo loads once require_engine has checked it can)

GROUND = "<include><uri>model://ground_plane</uri></include>"


def sdf(body: str, version: str = "1.6") -> str:
    return f'<sdf version="{version}"><world name="w">{body}</world></sdf>'


def write_model(folder: Path, name: str, body: str, config: bool = True) -> None:
    (folder / name).mkdir(parents=True)
    if config:
        (folder / name / "model.config").write_text(
            f'<model><name>{name}</name><sdf version="1.5">old.sdf</sdf><sdf version="1.6">model.sdf</sdf></model>')
    (folder / name / "model.sdf").write_text(f'<sdf version="1.6">{body}</sdf>')


CRATE = """<model name="crate"><link name="link"><pose>0 0 0.25 0 0 0</pose>
  <collision name="c"><geometry><box><size>0.5 0.5 0.5</size></box></geometry></collision>
  <visual name="v"><geometry><box><size>0.5 0.5 0.5</size></box></geometry>
    <material><ambient>0 0 1 1</ambient><diffuse>0 0 0.8 1</diffuse></material></visual></link></model>"""


def test_includes_come_from_gazebo_model_path_with_name_pose_and_static(tmp_path: Path) -> None:
    write_model(tmp_path, "crate", CRATE)
    resources = Resources.from_environment({"GAZEBO_MODEL_PATH": f"/nonexistent:{tmp_path}"})
    world = World.from_sdf(sdf(f"""{GROUND}<include><uri>model://sun</uri></include>
      <include><uri>model://crate</uri><name>crate_a</name><pose>1 2 0 0 0 1.5707963</pose></include>
      <include><uri>model://crate</uri><name>crate_b</name><pose>-1 0 3 0 0 0</pose><static>true</static>
        <plugin name="mover" filename="libmover.so"><speed>2</speed></plugin></include>
      """), resources)
    assert [(p.name, p.model, p.parameters()) for p in world.plugins()] == [("mover", "crate_b", {"speed": "2"})]
    assert world.model_names() == ["ground_plane", "crate_a", "crate_b"]
    assert [light.name for light in world.lights] == ["sun"]
    world.step(1000)
    a, b = world.model_state("crate_a").pose, world.model_state("crate_b").pose
    assert a.position == pytest.approx((1.0, 2.0, 0.0), abs=2e-3) and a.rpy()[2] == pytest.approx(math.pi / 2, abs=1e-3)
    assert b.position == pytest.approx((-1.0, 0.0, 3.0))  # static: it hangs in the air
    assert world.link_state("crate_a::link").pose.position[2] == pytest.approx(0.25, abs=2e-3)
    colors = {v.link: v.color for v in world.visuals()}
    assert colors["crate_a::link"] == (0.0, 0.0, 0.8, 1.0)  # <diffuse> wins over <ambient>
    assert colors["ground_plane::link"] == pytest.approx((0.7, 0.7, 0.7, 1.0))  # Gazebo/Grey


def test_an_included_model_folder_may_hold_a_urdf(tmp_path: Path) -> None:
    (tmp_path / "arm").mkdir()
    (tmp_path / "arm" / "model.config").write_text('<model><name>arm</name><sdf version="1.6">arm.urdf</sdf></model>')
    (tmp_path / "arm" / "arm.urdf").write_text("""<robot name="arm"><link name="base">
      <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link></robot>""")
    include = "<include><uri>model://arm</uri><name>left_arm</name><pose>0 0 2 0 0 0</pose></include>"
    world = World.from_sdf(sdf(include), Resources((str(tmp_path),)))
    assert world.link_names("left_arm") == ["left_arm::base"]
    assert world.model_state("left_arm").pose.position == pytest.approx((0.0, 0.0, 2.0))


def test_a_model_folder_without_model_config_uses_model_sdf(tmp_path: Path) -> None:
    write_model(tmp_path, "crate", CRATE, config=False)
    world = World.from_sdf(sdf("<include><uri>model://crate</uri></include>"), Resources((str(tmp_path),)))
    assert world.model_names() == ["crate"]


RELATIVE = """<model name="arm"><static>true</static><pose>1 0 0 0 0 0</pose>
  <frame name="mount"><pose>0 0 1 0 0 0</pose></frame>
  <link name="base"><pose relative_to="mount">0 0 0.5 0 0 1.5707963</pose></link>
  <link name="tip"><pose relative_to="base">1 0 0 0 0 0</pose>
    <visual name="v"><pose relative_to="mount">0 0 0 0 0 0</pose><geometry><sphere><radius>0.1</radius></sphere>
    </geometry></visual></link>
  <joint name="j" type="fixed"><parent>base</parent><child>tip</child></joint>
</model>"""


def test_relative_to_poses_chain_through_frames_and_links() -> None:
    world = World.from_sdf(sdf(RELATIVE, "1.7"))
    assert world.link_state("arm::base").pose.position == pytest.approx((1.0, 0.0, 1.5))
    # tip is 1 m along base's x, which the yaw turned to the world's y
    assert world.link_state("arm::tip").pose.position == pytest.approx((1.0, 1.0, 1.5), abs=1e-6)
    visual = next(v for v in world.visuals() if v.link == "arm::tip")
    in_world = world.link_state("arm::tip").pose * visual.pose
    assert in_world.position == pytest.approx((1.0, 0.0, 1.0), abs=1e-6)  # at the mount frame


def test_sdf_1_5_frame_attribute_and_nested_models_are_flattened() -> None:
    world = World.from_sdf(sdf("""<model name="outer"><static>true</static>
      <link name="a"><pose>0 0 1 0 0 0</pose></link>
      <model name="inner"><pose>2 0 0 0 0 0</pose><link name="b"><pose>0 0 1 0 0 0</pose></link></model>
      <joint name="j" type="fixed"><parent>a</parent><child>inner::b</child></joint></model>""", "1.5"))
    assert world.link_names("outer") == ["outer::a", "outer::inner::b"]
    assert world.link_state("outer::inner::b").pose.position == pytest.approx((2.0, 0.0, 1.0))


def hinged(joint: str) -> str:
    return f"""<model name="m"><link name="base"><pose>0 0 1 0 0 0</pose></link>
      <link name="arm"><pose>0 0 1 0 0 0</pose>
        <inertial><mass>1</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial></link>
      <joint name="fix" type="fixed"><parent>world</parent><child>base</child></joint>{joint}</model>"""


def test_revolute_limits_hold_an_effort_and_damping_slows() -> None:
    world = World.from_sdf(sdf(hinged("""<joint name="hinge" type="revolute"><parent>base</parent><child>arm</child>
      <axis><xyz>0 0 1</xyz><limit><lower>-0.5</lower><upper>0.5</upper><effort>2</effort></limit>
      <dynamics><damping>0.0</damping></dynamics></axis></joint>""")))
    assert world.joint_names("m") == ["m::fix", "m::hinge"]
    world.apply_joint_effort("m::hinge", 50.0, duration=2.0)  # limited to the joint's effort of 2
    world.step(100)
    state = world.joint_state("m::hinge")
    # 2 N m on 0.1 kg m^2 for 0.1 s: 2 rad/s, 0.1 rad (not 50 N m's 50 rad/s)
    assert state.velocity[0] == pytest.approx(2.0, rel=0.02) and state.position[0] == pytest.approx(0.1, rel=0.03)
    world.step(2000)
    assert world.joint_state("m::hinge").position[0] == pytest.approx(0.5, abs=0.01)  # held at the upper limit
    world.clear_joint_forces()
    world.reset_world()
    assert world.joint_state("m::hinge").position[0] == 0.0 and world.sim_time > 2.0


def test_damping_and_prismatic_and_ball_joints() -> None:
    damped = World.from_sdf(sdf(hinged("""<joint name="slide" type="prismatic"><parent>base</parent><child>arm</child>
      <axis><xyz>1 0 0</xyz><dynamics><damping>2.0</damping></dynamics></axis></joint>""")))
    damped.apply_joint_effort("m::slide", 1.0)
    damped.step(5000)
    assert damped.joint_state("m::slide").velocity[0] == pytest.approx(0.5, rel=0.01)  # force / damping
    ball = World.from_sdf(sdf(hinged("""<joint name="ball" type="ball"><parent>base</parent><child>arm</child>
      </joint>""")))
    assert len(ball.joint_state("m::ball").position) == 4 and len(ball.joint_state("m::ball").velocity) == 3


def test_a_joint_spring_oscillates_about_its_reference() -> None:
    world = World.from_sdf(sdf(hinged("""<joint name="hinge" type="revolute"><parent>base</parent><child>arm</child>
      <axis><xyz>0 0 1</xyz><dynamics><spring_stiffness>0.4</spring_stiffness><spring_reference>0.3</spring_reference>
      </dynamics></axis></joint>""")))
    crossings: list[float] = []
    before = world.joint_state("m::hinge").position[0] - 0.3
    while len(crossings) < 3:
        world.step()
        now = world.joint_state("m::hinge").position[0] - 0.3
        if (before > 0 >= now) or (before < 0 <= now):
            crossings.append(world.sim_time)
        before = now
    # 0.1 kg m^2 on 0.4 N m/rad: a period of 2 pi sqrt(0.1 / 0.4) = pi s, about 0.3 rad
    assert crossings[2] - crossings[0] == pytest.approx(math.pi, rel=0.01)


def test_sdf_1_4_axes_are_in_the_model_frame() -> None:
    body = hinged("""<joint name="hinge" type="revolute"><parent>base</parent><child>arm</child>
      <pose>0 0 0 1.5707963 0 0</pose><axis><xyz>0 0 1</xyz></axis></joint>""")
    for version, turns_about_world_z in (("1.4", True), ("1.6", False)):
        world = World.from_sdf(sdf(body, version))
        world.physics = Physics(gravity=(0.0, 0.0, 0.0))
        world.apply_joint_effort("m::hinge", 1.0)
        world.step(100)
        angular = world.link_state("m::arm").angular
        assert (abs(angular[2]) > 0.5) == turns_about_world_z


def test_a_link_without_gravity_floats() -> None:
    world = World.from_sdf(sdf("""<model name="balloon"><pose>0 0 5 0 0 0</pose><link name="link">
      <gravity>false</gravity></link></model>"""))
    world.step(500)
    assert world.model_state("balloon").pose.position[2] == pytest.approx(5.0)


STL = """solid tetra
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 0 1 0
  vertex 1 0 0
 endloop
endfacet
facet normal 0 -1 0
 outer loop
  vertex 0 0 0
  vertex 1 0 0
  vertex 0 0 1
 endloop
endfacet
facet normal -1 0 0
 outer loop
  vertex 0 0 0
  vertex 0 0 1
  vertex 0 1 0
 endloop
endfacet
facet normal 1 1 1
 outer loop
  vertex 1 0 0
  vertex 0 1 0
  vertex 0 0 1
 endloop
endfacet
endsolid tetra
"""
OBJ = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"


def test_meshes_through_package_and_file_uris(tmp_path: Path) -> None:
    (tmp_path / "pkg" / "meshes").mkdir(parents=True)
    (tmp_path / "pkg" / "meshes" / "tetra.stl").write_text(STL)
    (tmp_path / "tetra.obj").write_text(OBJ)
    asked: list[str] = []

    def find(package: str) -> str | None:
        asked.append(package)
        return str(tmp_path / package) if package == "pkg" else None

    world = World.from_sdf(sdf(f"""{GROUND}<model name="rock"><pose>0 0 1 0 0 0</pose><link name="link">
      <collision name="c"><geometry><mesh><uri>package://pkg/meshes/tetra.stl</uri><scale>0.5 0.5 0.5</scale>
      </mesh></geometry></collision>
      <visual name="v"><geometry><mesh><uri>file://{tmp_path}/tetra.obj</uri></mesh></geometry></visual>
      </link></model>"""), Resources(find_package=find))
    assert asked == ["pkg"]
    (visual,) = [v for v in world.visuals() if v.link == "rock::link"]
    assert visual.kind == "mesh" and visual.triangles is not None and visual.triangles.shape == (12, 3)
    world.step(2000)
    assert world.model_state("rock").pose.position[2] < 0.05  # the collision hull rests on the ground


def test_a_collada_mesh_keeps_its_scene_transform(tmp_path: Path) -> None:
    import trimesh

    box = trimesh.creation.box((0.2, 0.4, 0.6))
    box.apply_translation((1.0, 0.0, 0.0))
    box.export(str(tmp_path / "box.dae"))
    world = World.from_sdf(sdf(f"""<model name="m"><static>true</static><link name="link"><visual name="v">
      <geometry><mesh><uri>{tmp_path}/box.dae</uri><scale>2 2 2</scale></mesh></geometry></visual></link></model>"""))
    (visual,) = world.visuals()
    assert visual.triangles is not None and len(visual.triangles) == 36
    assert visual.triangles.min(axis=0) == pytest.approx((1.8, -0.4, -0.6), abs=1e-5)
    assert visual.triangles.max(axis=0) == pytest.approx((2.2, 0.4, 0.6), abs=1e-5)


URDF = """<robot name="bot">
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <link name="base_link">
    <inertial><origin xyz="0 0 0"/><mass value="2"/><inertia ixx="0.02" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/>
    </inertial>
    <visual><geometry><box size="0.4 0.3 0.1"/></geometry><material name="blue"/></visual>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
  <link name="wheel">
    <inertial><mass value="0.2"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><cylinder radius="0.05" length="0.02"/></geometry></visual>
    <collision><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision>
  </link>
  <link name="laser_link"/>
  <joint name="wheel_joint" type="continuous"><parent link="base_link"/><child link="wheel"/>
    <origin xyz="0 0.2 0" rpy="-1.5707963 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="laser_joint" type="fixed"><parent link="base_link"/><child link="laser_link"/>
    <origin xyz="0.1 0 0.1"/></joint>
  <gazebo reference="wheel"><material>Gazebo/Red</material><mu1>0.8</mu1><mu2>0.6</mu2></gazebo>
  <gazebo reference="laser_link">
    <sensor name="hokuyo" type="ray"><pose>0 0 0 0 0 0</pose><update_rate>40</update_rate>
      <ray><scan><horizontal><samples>3</samples><min_angle>-0.1</min_angle><max_angle>0.1</max_angle></horizontal>
      </scan><range><min>0.1</min><max>30</max></range></ray>
      <plugin name="laser" filename="libgazebo_ros_laser.so"><topicName>scan</topicName></plugin>
    </sensor>
  </gazebo>
  <gazebo><plugin name="drive" filename="libgazebo_ros_diff_drive.so"><wheelSeparation>0.4</wheelSeparation>
    <commandTopic>cmd_vel</commandTopic></plugin></gazebo>
</robot>"""


def test_urdf_with_gazebo_tags_spawns_as_spawn_model_reads_it() -> None:
    world = World.from_sdf(sdf(GROUND))
    name = world.spawn_urdf(URDF, "robot", Pose((1.0, 0.0, 0.5)))
    assert name == "robot" and world.model_names() == ["ground_plane", "robot"]
    assert world.link_names("robot") == ["robot::base_link", "robot::wheel", "robot::laser_link"]
    assert world.link_state("robot::laser_link").pose.position == pytest.approx((1.1, 0.0, 0.6))
    colors = {v.link: v.color for v in world.visuals()}
    assert colors["robot::base_link"] == (0.0, 0.0, 1.0, 1.0) and colors["robot::wheel"] == (1.0, 0.0, 0.0, 1.0)
    wheel = world.model_description("robot").link("wheel")
    assert wheel is not None and (wheel.collisions[0].name, wheel.collisions[0].mu, wheel.collisions[0].mu2) == (
        "wheel_collision", 0.8, 0.6)
    assert wheel.collisions[0].gazebo_name == "wheel::wheel_collision"  # on a continuous joint: not lumped
    (sensor,) = world.sensors()
    assert (sensor.link, sensor.name, sensor.type, sensor.update_rate) == ("robot::laser_link", "hokuyo", "ray", 40.0)
    plugins = {p.name: p for p in world.plugins()}
    assert plugins["drive"].filename == "libgazebo_ros_diff_drive.so" and plugins["drive"].model == "robot"
    assert plugins["drive"].parameters() == {"wheelSeparation": "0.4", "commandTopic": "cmd_vel"}
    assert (plugins["laser"].link, plugins["laser"].sensor) == ("laser_link", "hokuyo")
    world.step(500)
    assert world.model_state("robot").pose.position[2] < 0.5  # it fell onto the ground
    links = world.link_states()
    assert list(links) == ["ground_plane::link", "robot::base_link", "robot::wheel", "robot::laser_link"]
    assert links["robot::wheel"] == world.link_state("robot::wheel")
    assert world.model_states() == {name: world.model_state(name) for name in ("ground_plane", "robot")}


def test_spawning_and_deleting_keeps_the_others_state() -> None:
    world = World.from_sdf(sdf(f"""{GROUND}<include><uri>model://sphere</uri><pose>0 0 5 0 0 0</pose></include>"""))
    world.step(300)
    before = world.model_state("sphere")
    world.spawn_sdf((Path(SHIPPED_MODELS) / "box" / "model.sdf").read_text(), "box", Pose((3.0, 0.0, 0.5)))
    after = world.model_state("sphere")
    assert after.pose.position == pytest.approx(before.pose.position) and after.linear == pytest.approx(before.linear)
    assert world.sim_time == pytest.approx(0.3) and world.generation == 2
    world.delete_model("box")
    assert world.model_names() == ["ground_plane", "sphere"]
    assert world.model_state("sphere").linear == pytest.approx(before.linear)


def test_a_body_wrench_for_a_duration_gives_its_impulse_and_torque_from_its_point() -> None:
    world = World.from_sdf(sdf("""<model name="puck"><pose>0 0 0 0 0 0</pose><link name="link">
      <gravity>false</gravity><inertial><mass>2</mass><inertia><ixx>0.5</ixx><iyy>0.5</iyy><izz>0.5</izz></inertia>
      </inertial></link></model>"""))
    world.apply_body_wrench("puck::link", (4.0, 0.0, 0.0), duration=0.5)
    world.step(1000)
    assert world.model_state("puck").linear == pytest.approx((1.0, 0.0, 0.0), rel=1e-3)  # 4 N x 0.5 s / 2 kg
    # a force at 1 m along y pushes and turns: torque (0, 1, 0) x (1, 0, 0) = -1 about z
    world.apply_body_wrench("puck::link", (1.0, 0.0, 0.0), reference_point=(0.0, 1.0, 0.0), start=world.sim_time,
                            duration=0.1)
    world.step(200)
    assert world.model_state("puck").angular[2] == pytest.approx(-0.1 / 0.5, rel=1e-2)
    world.apply_body_wrench("puck::link", (1.0, 0.0, 0.0))
    world.clear_body_wrenches("puck::link")
    speed = world.model_state("puck").linear[0]
    world.step(100)
    assert world.model_state("puck").linear[0] == pytest.approx(speed)


def test_reset_simulation_rewinds_time_and_reset_world_keeps_it() -> None:
    world = World.from_sdf(sdf(f"{GROUND}<include><uri>model://box</uri><pose>0 0 3 0 0 0</pose></include>"))
    world.step(500)
    world.reset_world()
    assert world.sim_time == pytest.approx(0.5) and world.model_state("box").pose.position[2] == pytest.approx(3.0)
    world.step(100)
    world.reset_simulation()
    assert world.sim_time == 0.0 and world.iterations == 0
    assert world.model_state("box").pose.position[2] == pytest.approx(3.0)
    assert world.model_state("box").linear == (0.0, 0.0, 0.0)


def test_a_moved_static_model_goes_back_on_reset() -> None:
    world = World.from_sdf(sdf(GROUND + """<include><uri>model://box</uri><pose>0 0 0.5 0 0 0</pose>
      <static>true</static></include>"""))
    world.set_model_state("box", State(Pose((2.0, 1.0, 0.5))))
    world.step(10)
    assert world.model_state("box").pose.position == pytest.approx((2.0, 1.0, 0.5))
    world.spawn_sdf((Path(SHIPPED_MODELS) / "sphere" / "model.sdf").read_text(), "ball", Pose((5.0, 0.0, 1.0)))
    assert world.model_state("box").pose.position == pytest.approx((2.0, 1.0, 0.5))  # kept through a rebuild
    world.reset_world()
    assert world.model_state("box").pose.position == pytest.approx((0.0, 0.0, 0.5))


def test_set_model_state_moves_and_launches_a_model() -> None:
    world = World.from_sdf(sdf("<include><uri>model://box</uri><pose>0 0 3 0 0 0</pose></include>"))
    world.physics = Physics(gravity=(0.0, 0.0, 0.0))
    turned = Pose((5.0, 1.0, 2.0), (0.0, 0.0, math.sin(0.5), math.cos(0.5)))
    world.set_model_state("box", State(turned, (1.0, 0.0, 0.0), (0.0, 0.0, 0.5)))
    got = world.model_state("box")
    assert got.pose.position == pytest.approx(turned.position) and got.angular == pytest.approx((0.0, 0.0, 0.5))
    world.step(1000)
    assert world.model_state("box").pose.position[0] == pytest.approx(6.0, rel=1e-3)
    assert world.model_state("box").pose.rpy()[2] == pytest.approx(1.5, rel=1e-3)


def test_a_models_twist_is_set_where_it_is() -> None:
    world = World.from_sdf(sdf("<include><uri>model://box</uri><pose>1 2 3 0 0 1</pose></include>"))
    world.physics = Physics(gravity=(0.0, 0.0, 0.0))
    world.set_model_twist("box", (0.5, 0.0, 0.0), (0.0, 0.0, 0.2))
    state = world.model_state("box")
    assert state.pose.position == pytest.approx((1.0, 2.0, 3.0)) and state.angular == pytest.approx((0.0, 0.0, 0.2))
    world.step(1000)
    assert world.model_state("box").pose.position[0] == pytest.approx(1.5, rel=1e-3)
    assert world.model_state("box").pose.rpy()[2] == pytest.approx(1.2, rel=1e-3)


@pytest.mark.usefixtures("renders")
@in_own_process
def test_world_and_sensor_plugins_and_physics_are_read() -> None:
    world = World.from_sdf(sdf("""<physics type="ode"><max_step_size>0.002</max_step_size>
      <real_time_update_rate>500</real_time_update_rate><real_time_factor>2</real_time_factor></physics>
      <plugin name="ros_api" filename="libgazebo_ros_api_plugin.so"/>
      <model name="cam"><static>true</static><link name="link"><sensor name="eye" type="camera">
        <camera><image><width>64</width><height>48</height></image></camera>
        <plugin name="camera_controller" filename="libgazebo_ros_camera.so"><cameraName>eye</cameraName>
          <frameName>eye_link</frameName></plugin></sensor></link></model>"""))
    assert (world.physics.max_step_size, world.physics.real_time_update_rate, world.physics.real_time_factor) == (
        0.002, 500.0, 2.0)
    plugins = world.plugins()
    assert [(p.name, p.model, p.link, p.sensor) for p in plugins] == [
        ("ros_api", "", "", ""), ("camera_controller", "cam", "link", "eye")]
    assert plugins[1].element.child_text("frameName") == "eye_link"
    (sensor,) = world.sensors()
    assert sensor.config.as_dict()["camera"] == {"image": {"width": "64", "height": "48"}}
    frame = world.camera_frame(sensor)
    assert frame.rgb is not None and frame.rgb.shape == (48, 64, 3) and np.asarray(frame.config.k()).shape == (9,)
    world.close()


def siblings(self_collide: str) -> str:
    def child(name: str, x: float) -> str:
        return f"""<link name="{name}"><pose>{x} 0 1 0 0 0</pose>{self_collide}
          <collision name="c"><geometry><box><size>0.3 0.3 0.3</size></box></geometry></collision></link>
          <joint name="{name}_joint" type="revolute"><parent>base</parent><child>{name}</child>
          <axis><xyz>0 0 1</xyz></axis></joint>"""

    return f"""<model name="m"><link name="base"><pose>0 0 1 0 0 0</pose><gravity>false</gravity></link>
      <joint name="fix" type="fixed"><parent>world</parent><child>base</child></joint>
      {child("a", 0.1)}{child("b", -0.1)}</model>"""


def test_a_models_links_touch_each_other_only_where_they_self_collide() -> None:
    apart = World.from_sdf(sdf(siblings("")))
    assert apart.contacts("m::a") == []
    together = World.from_sdf(sdf(siblings("<self_collide>true</self_collide>")))
    assert {c.collision2 for c in together.contacts("m::a")} == {"m::b::c"}


def test_a_urdf_link_named_world_holds_the_robot_in_place() -> None:
    world = World.from_sdf(sdf(GROUND))
    world.spawn_urdf("""<robot name="arm"><link name="world"/>
      <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
      </inertial></link>
      <joint name="anchor" type="fixed"><parent link="world"/><child link="base"/><origin xyz="0 0 1"/></joint>
      </robot>""", "arm", Pose((1.0, 0.0, 0.0)))
    world.step(500)
    assert world.link_names("arm") == ["arm::base"]
    assert world.link_state("arm::base").pose.position == pytest.approx((1.0, 0.0, 1.0))


def test_worlds_are_found_on_gazebo_resource_path_then_kames(tmp_path: Path) -> None:
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "mine.world").write_text(sdf(GROUND))
    resources = Resources.from_environment({"GAZEBO_RESOURCE_PATH": str(tmp_path)})
    assert resources.world_file("worlds/mine.world") == str(tmp_path / "worlds" / "mine.world")
    empty = World.from_file(resources.world_file("worlds/empty.world"), resources)
    assert empty.model_names() == ["ground_plane"] and [light.name for light in empty.lights] == ["sun"]
    with pytest.raises(GazeboError, match=f"world file worlds/none.world not found, nor in GAZEBO_RESOURCE_PATH "
                                          f"\\({tmp_path}\\)"):
        resources.world_file("worlds/none.world")


def test_an_empty_world_runs_and_takes_models() -> None:
    world = World.empty()
    world.step(10)
    assert world.model_names() == [] and world.sim_time == pytest.approx(0.01)
    world.spawn_sdf((Path(SHIPPED_MODELS) / "box" / "model.sdf").read_text(), "box", Pose((0.0, 0.0, 1.0)))
    world.step(100)
    assert world.model_state("box").pose.position[2] == pytest.approx(1.0 - 0.5 * 9.8 * 0.1 ** 2, abs=1e-3)


def test_a_planes_visual_faces_its_normal() -> None:
    world = World.from_sdf(sdf("""<model name="wall"><static>true</static><link name="link"><visual name="v">
      <geometry><plane><normal>1 0 0</normal><size>4 2</size></plane></geometry></visual></link></model>"""))
    (plane,) = world.visuals()
    assert (plane.kind, plane.size) == ("plane", (4.0, 2.0))
    assert plane.pose.rotation() @ np.array((0.0, 0.0, 1.0)) == pytest.approx((1.0, 0.0, 0.0))


def test_urdf_collisions_carry_the_names_gazebos_lumping_gives_them() -> None:
    box = "<collision><geometry><box size='0.1 0.1 0.1'/></geometry></collision>"
    world = World.empty()
    world.spawn_urdf(f"""<robot name="kobuki"><link name="base_footprint"/><link name="base_link">{box}{box}</link>
      <link name="plate">{box}</link><link name="wheel">{box}</link>
      <joint name="a" type="fixed"><parent link="base_footprint"/><child link="base_link"/></joint>
      <joint name="b" type="fixed"><parent link="base_link"/><child link="plate"/><origin xyz="0 0 0.2"/></joint>
      <joint name="c" type="continuous"><parent link="base_link"/><child link="wheel"/><origin xyz="0 0.3 0"/></joint>
      </robot>""", pose=Pose((0.0, 0.0, 1.0)))
    names = {link.name: [(c.name, c.gazebo_name) for c in link.collisions]
             for link in world.model_description("kobuki").links}
    assert names == {
        "base_footprint": [],
        "base_link": [("base_link_collision", "base_footprint::base_footprint_fixed_joint_lump__base_link_collision"),
                      ("base_link_collision_1",
                       "base_footprint::base_footprint_fixed_joint_lump__base_link_collision_1")],
        "plate": [("plate_collision", "base_footprint::base_footprint_fixed_joint_lump__plate_collision")],
        "wheel": [("wheel_collision", "wheel::wheel_collision")]}
    assert world.gazebo_collision_name("kobuki::plate::plate_collision") == (
        "kobuki::base_footprint::base_footprint_fixed_joint_lump__plate_collision")
    assert world.gazebo_collision_name("kobuki::wheel::wheel_collision") == "kobuki::wheel::wheel_collision"
    assert world.gazebo_collision_name("elsewhere::l::c") == "elsewhere::l::c"
