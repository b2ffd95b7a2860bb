"""gzserver live, as the courses run it: `roslaunch gazebo_ros empty_world.launch` (headless),
`rosrun gazebo_ros spawn_model -urdf -param ...`, Debian's rosservice asking /gazebo/get_model_state,
and a URDF robot's plugins: its laser against a known wall, its camera's image and CameraInfo,
diff drive's odometry along the commanded arc; pause, unpause and reset; the unknown plugin's
warning; bad requests answered, the server running on."""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml

from tests.gazebo_ros.gazebo_sim import DATA, debian_message_packages, gazebo
from tests.support import SYSTEM_PYTHON, Proc, have_debian_ros
from tests.turtlesim.sim import BIN, Sim, wait_until

# through kame.gazebo.engine, which chooses the headless renderer before MuJoCo loads (a bare `import
# mujoco` would fix its GL back end for every later test in this process)
pytest.importorskip("kame.gazebo.engine", reason="kame[gazebo] (MuJoCo) is not installed")

BOX_URDF = """<robot name="box"><link name="base_link">
  <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  <visual><geometry><box size="0.2 0.2 0.2"/></geometry></visual></link></robot>"""
RED_PLATE = """<sdf version="1.6"><model name="plate"><static>true</static><link name="link">
  <collision name="c"><geometry><box><size>0.02 0.2 0.2</size></box></geometry></collision>
  <visual name="v"><geometry><box><size>0.02 0.2 0.2</size></box></geometry>
  <material><script><name>Gazebo/Red</name></script></material></visual></link></model></sdf>"""


@pytest.fixture(scope="module")
def live(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[Sim, Proc]]:
    home = tmp_path_factory.mktemp("gazebo")
    with gazebo(home, "paused:=true", f"world_name:={DATA / 'walls.world'}") as running:
        yield running


def call(sim: Sim, service: str, *args: str) -> dict[str, Any]:
    out = sim.run("rosservice", "call", service, *args, timeout=30).stdout
    data = yaml.safe_load(out) if out.strip() else {}
    return data if isinstance(data, dict) else {}


def spawn(sim: Sim, *args: str) -> str:
    result = sim.run("rosrun", "gazebo_ros", "spawn_model", *args, check=False, timeout=60)
    return result.stdout + result.stderr


def test_spawn_model_then_debian_rosservice_gets_its_state(live: tuple[Sim, Proc], tmp_path: Path) -> None:
    sim, _ = live
    (tmp_path / "box.urdf").write_text(BOX_URDF)
    sim.run("rosparam", "set", "/box_description", "-t", str(tmp_path / "box.urdf"))
    out = spawn(sim, "-urdf", "-param", "box_description", "-model", "box", "-x", "-1", "-z", "1")
    assert "Spawn status: SpawnModel: Successfully spawned entity" in out
    assert "box" in call(sim, "/gazebo/get_world_properties")["model_names"]
    if not have_debian_ros():
        pytest.skip("Debian's ROS 1 is not installed")
    env = dict(sim.env, PYTHONPATH=str(debian_message_packages(tmp_path / "debian")))
    answer = Proc([SYSTEM_PYTHON, "/usr/bin/rosservice", "call", "/gazebo/get_model_state",
                   "{model_name: box, relative_entity_name: world}"], env)
    answer.popen.wait(30)
    out, err = answer.stop()
    state = yaml.safe_load(out)
    assert state["success"] is True and state["status_message"] == "GetModelState: got properties", err
    assert state["pose"]["position"] == {"x": -1.0, "y": 0.0, "z": 1.0}  # paused: where it was spawned
    assert state["header"]["frame_id"] == "world"


def test_pause_unpause_and_reset(live: tuple[Sim, Proc]) -> None:
    sim, _ = live

    def box_z() -> float:
        return float(call(sim, "/gazebo/get_model_state", "box", "")["pose"]["position"]["z"])

    assert call(sim, "/gazebo/get_physics_properties")["pause"] is True
    call(sim, "/gazebo/unpause_physics")
    wait_until(lambda: box_z() < 0.11, timeout=30, what="the box to fall onto the ground")
    assert box_z() == pytest.approx(0.1, abs=0.005)
    push = call(sim, "/gazebo/apply_body_wrench",
                "{body_name: 'box::base_link', wrench: {force: {z: 12}}, duration: {secs: -1}}")
    # 12 N up on 1 kg: it rises at 2.2 m/s^2 until the wrench is cleared. Gently, so that the seconds each
    # service call takes on a loaded machine leave it tens of metres up, not hundreds
    assert push["success"] is True
    wait_until(lambda: box_z() > 0.5, timeout=30, what="the wrench to lift the box")
    call(sim, "/gazebo/clear_body_wrenches", "box::base_link")
    wait_until(lambda: box_z() < 0.11, timeout=60, what="the box to fall back")
    call(sim, "/gazebo/pause_physics")
    time_paused = call(sim, "/gazebo/get_world_properties")["sim_time"]
    assert call(sim, "/gazebo/get_world_properties")["sim_time"] == time_paused
    call(sim, "/gazebo/reset_simulation")
    assert call(sim, "/gazebo/get_world_properties")["sim_time"] == 0.0
    assert box_z() == pytest.approx(1.0)
    sim.run("rostopic", "pub", "-1", "/gazebo/set_model_state", "gazebo_msgs/ModelState",
            "{model_name: box, pose: {position: {x: 1.5, z: 2}, orientation: {w: 1}}, reference_frame: world}")
    wait_until(lambda: box_z() == pytest.approx(2.0), timeout=20, what="/gazebo/set_model_state to move the box")
    link = call(sim, "/gazebo/get_link_state", "box::base_link", "box")  # the link seen from its own model
    assert link["success"] is True and link["link_state"]["pose"]["position"] == {"x": 0.0, "y": 0.0, "z": 0.0}
    deleted = call(sim, "/gazebo/delete_model", "box")
    assert deleted == {"success": True, "status_message": "DeleteModel: successfully deleted model"}


def test_robot_plugins_laser_camera_and_unknown(live: tuple[Sim, Proc]) -> None:
    sim, launch = live
    out = spawn(sim, "-urdf", "-file", str(DATA / "robot.urdf"), "-model", "rover", "-J", "left_wheel_joint", "0.5",
                "-unpause")
    assert "Successfully spawned entity" in out
    assert "Set model configuration status: SetModelConfiguration: success" in out
    assert call(sim, "/gazebo/get_physics_properties")["pause"] is False  # -unpause
    assert 0 < sim.echo("/gazebo/performance_metrics")["real_time_factor"] < 1.2  # paced at 1, slower under load
    joints = sim.echo("/joint_states")
    assert joints["name"] == ["left_wheel_joint", "right_wheel_joint", "laser_joint"]
    assert joints["position"][0] == pytest.approx(0.5, abs=0.05) and joints["position"][2] == 0.0  # -J; fixed
    warnings = [line for line in launch.out + launch.err if "libgazebo_ros_control.so" in line]
    assert len(warnings) == 1 and "kame has no libgazebo_ros_control.so" in warnings[0]
    scan = sim.echo("/scan")
    ranges = [float(r) for r in scan["ranges"]]  # rostopic prints inf, which YAML reads as text
    assert len(ranges) == 181 and scan["header"]["frame_id"] == "laser_link"
    # the wall's near face is at x = 2, the laser 0.1 m ahead of the robot's centre
    assert ranges[90] == pytest.approx(1.9, abs=0.01)
    assert ranges[60] == pytest.approx(1.9 / math.cos(math.radians(30)), abs=0.01)
    assert ranges[0] == math.inf  # along the wall: nothing within range
    plate = call(sim, "/gazebo/spawn_sdf_model", "plate", RED_PLATE, "", "{position: {x: 1.15, y: 0.3, z: 0.115}}", "")
    assert plate["success"] is True, plate
    info = sim.echo("/front_camera/camera_info")
    assert (info["width"], info["height"], info["header"]["frame_id"]) == (160, 120, "camera_link")
    f, cx, cy = info["K"][0], info["K"][2], info["K"][5]
    assert f == pytest.approx(160 / (2 * math.tan(0.5)))
    assert (cx, cy) == ((160 - 1) / 2, (120 - 1) / 2)  # the image's centre, where the renderer puts the axis
    image = sim.run("rostopic", "echo", "-n", "1", "--noarr", "/front_camera/image_raw", timeout=20).stdout
    assert "encoding: \"rgb8\"" in image and "height: 120" in image


def test_red_plate_at_the_pixels_k_predicts(live: tuple[Sim, Proc]) -> None:
    """The plate spawned in front of the camera (its centre 0.3 m left at 1 m) where K puts it."""
    sim, _ = live
    found: list[np.ndarray] = []

    def red_pixels() -> bool:
        out = sim.run("rostopic", "echo", "-n", "1", "/front_camera/image_raw", timeout=30).stdout
        msg = yaml.safe_load(out.split("---")[0])
        pixels = np.array(msg["data"], dtype=np.uint8).reshape(msg["height"], msg["width"], 3).astype(int)
        found[:] = [(pixels[:, :, 0] > 80) & (pixels[:, :, 0] > 2 * pixels[:, :, 1])
                    & (pixels[:, :, 0] > 2 * pixels[:, :, 2])]
        return int(found[0].sum()) > 50

    wait_until(red_pixels, timeout=30, what="an image with the red plate in it")
    rows, columns = np.nonzero(found[0])
    k = sim.echo("/front_camera/camera_info")["K"]
    distance = 1.14 - 0.15  # the plate's face from the camera (at x = 0.15); its centre 0.3 m to the left
    assert columns.mean() == pytest.approx(k[2] - k[0] * 0.3 / distance, abs=1.0)
    assert rows.mean() == pytest.approx(k[5], abs=1.0)


def test_diff_drive_follows_the_commanded_arc(live: tuple[Sim, Proc]) -> None:
    sim, _ = live
    call(sim, "/gazebo/reset_world")
    driver = Proc([str(BIN / "rostopic"), "pub", "-r", "20", "/cmd_vel", "geometry_msgs/Twist",
                   "{linear: {x: 0.2}, angular: {z: 0.2}}"], sim.env, cwd=sim.home)
    sim.procs.append(driver)

    def odom() -> tuple[float, float, float]:
        pose = sim.echo("/odom")["pose"]["pose"]
        q = pose["orientation"]
        yaw = math.atan2(2 * (q["w"] * q["z"] + q["x"] * q["y"]), 1 - 2 * (q["y"] ** 2 + q["z"] ** 2))
        return pose["position"]["x"], pose["position"]["y"], yaw

    wait_until(lambda: odom()[2] > 0.6, timeout=60, what="the robot to turn 0.6 rad")
    x, y, yaw = odom()
    # a twist of 0.2 m/s and 0.2 rad/s drives a circle of 1 m about (0, 1): where the heading puts it
    assert math.dist((x, y), (math.sin(yaw), 1 - math.cos(yaw))) < 0.05
    driver.stop()


def test_robot_namespace_puts_a_second_robots_topics_under_it(live: tuple[Sim, Proc]) -> None:
    sim, _ = live
    out = spawn(sim, "-urdf", "-file", str(DATA / "robot.urdf"), "-model", "rover2", "-robot_namespace", "r2",
                "-y", "-1.5")
    assert "Successfully spawned entity" in out
    odom = sim.echo("/r2/odom")  # the plugins' topics under the namespace, their frames as given (no tf_prefix)
    assert (odom["header"]["frame_id"], odom["child_frame_id"]) == ("odom", "base_footprint")
    assert odom["pose"]["pose"]["position"]["y"] == pytest.approx(-1.5, abs=0.01)
    assert sim.echo("/r2/front_camera/camera_info")["width"] == 160
    assert call(sim, "/gazebo/delete_model", "rover2")["success"] is True


def test_spawn_model_waits_for_a_model_and_bonds_to_its_own(live: tuple[Sim, Proc], tmp_path: Path) -> None:
    sim, _ = live
    (tmp_path / "box.urdf").write_text(BOX_URDF)
    bonded = Proc([str(BIN / "rosrun"), "gazebo_ros", "spawn_model", "-urdf", "-file", str(tmp_path / "box.urdf"),
                   "-model", "bonded", "-x", "-2", "-z", "0.5", "-wait", "rover", "-b"], sim.env, cwd=tmp_path)
    sim.procs.append(bonded)
    bonded.wait_line("Waiting for shutdown to delete model bonded", timeout=60)
    assert "bonded" in call(sim, "/gazebo/get_world_properties")["model_names"]
    bonded.stop(timeout=30)  # Ctrl-C: -b deletes the model on the way out
    assert "bonded" not in call(sim, "/gazebo/get_world_properties")["model_names"]


def test_spawn_sdf_file_places_the_models_own_pose_at_the_initial_pose(live: tuple[Sim, Proc]) -> None:
    sim, _ = live
    model = Path(__file__).resolve().parents[2] / "src" / "kame" / "gazebo" / "models" / "box" / "model.sdf"
    out = spawn(sim, "-sdf", "-file", str(model), "-model", "crate", "-x", "-3", "-y", "3", "-Y", "0.5")
    assert "Successfully spawned entity" in out
    state = call(sim, "/gazebo/get_model_state", "crate", "")
    # the model's <pose> (0 0 0.5) seen from the initial pose, as gazebo_ros's updateSDFAttributes puts it
    assert state["pose"]["position"]["x"] == pytest.approx(-3, abs=0.01)
    assert state["pose"]["position"]["z"] == pytest.approx(0.5, abs=0.01)
    assert call(sim, "/gazebo/delete_model", "crate")["success"] is True


def test_bad_requests_are_answered_and_the_server_runs_on(live: tuple[Sim, Proc], tmp_path: Path) -> None:
    sim, launch = live
    nan_state = call(sim, "/gazebo/set_model_state", "{model_state: {model_name: rover, pose: {position: {x: .nan}}}}")
    assert nan_state["success"] is False and "finite" in nan_state["status_message"]
    wrench = call(sim, "/gazebo/apply_body_wrench", "{body_name: 'rover::chassis', wrench: {force: {x: .inf}}}")
    assert wrench["success"] is False
    nan_pose = call(sim, "/gazebo/spawn_urdf_model", "nan_box", BOX_URDF, "", "{position: {x: .nan}}", "")
    assert nan_pose["success"] is False and "finite" in nan_pose["status_message"]
    malformed = call(sim, "/gazebo/spawn_urdf_model", "broken", "<robot name='x'><link", "", "{}", "")
    assert malformed["success"] is False and "not SDF or URDF" in malformed["status_message"]
    big_box = BOX_URDF.replace("0.2 0.2 0.2", "0.6 0.6 0.6")
    inside = call(sim, "/gazebo/spawn_urdf_model", "in_wall", big_box, "", "{position: {x: 2.1, z: 0.5}}", "")
    assert inside["success"] is False and "inside model 'wall'" in inside["status_message"]
    mesh = BOX_URDF.replace('<box size="0.2 0.2 0.2"/>', '<mesh filename="file:///nowhere/missing.stl"/>')
    missing = call(sim, "/gazebo/spawn_urdf_model", "meshy", mesh, "", "{position: {z: 3}}", "")
    assert missing["success"] is False and "missing.stl" in missing["status_message"]
    unknown = call(sim, "/gazebo/get_model_state", "nobody", "")
    assert unknown == {**unknown, "success": False, "status_message": "GetModelState: model does not exist"}
    assert launch.popen.poll() is None
    assert "rover" in call(sim, "/gazebo/get_world_properties")["model_names"]
    assert not any("Traceback" in line for line in launch.out + launch.err)
