"""The other plugins live, on one world (data/sensors.world): imu_sensor at rest, the bumper on the
ground, p3d's ground truth, planar_move and skid_steer_drive driven by cmd_vel, openni_kinect's depth
image, CameraInfo and cloud against a wall 1.5 m away, and block_laser's cloud."""

from __future__ import annotations

import math
import struct
from pathlib import Path

import pytest

from tests.gazebo_ros.gazebo_sim import DATA, gazebo
from tests.support import Proc
from tests.turtlesim.sim import BIN, wait_until

# through kame.gazebo.engine, which chooses the headless renderer before MuJoCo loads (a bare `import
# mujoco` would fix its GL back end for every later test in this process)
pytest.importorskip("kame.gazebo.engine", reason="kame[gazebo] (MuJoCo) is not installed")


def test_imu_bumper_p3d_drives_depth_camera_and_block_laser(tmp_path: Path) -> None:
    with gazebo(tmp_path, f"world_name:={DATA / 'sensors.world'}") as (sim, launch):
        imu = sim.echo("/probe/imu")
        assert imu["header"]["frame_id"] == "probe_imu"
        assert imu["linear_acceleration"]["z"] == pytest.approx(9.8, abs=0.1)  # gravity's reaction, at rest
        assert imu["orientation"]["w"] == pytest.approx(1.0, abs=1e-3)
        body_imu = sim.echo("/probe/imu_body")  # GazeboRosIMU: the body's change of velocity, no gravity
        assert body_imu["header"]["frame_id"] == "body"
        assert abs(body_imu["linear_acceleration"]["z"]) < 0.5 and body_imu["orientation"]["w"] == pytest.approx(1.0)
        bumper = sim.echo("/probe/bumper")
        assert bumper["states"] and all("ground_plane" in s["collision2_name"] for s in bumper["states"])
        assert bumper["states"][0]["collision1_name"] == "probe::body::collision"
        truth = sim.echo("/probe/ground_truth")
        assert (truth["header"]["frame_id"], truth["child_frame_id"]) == ("world", "body")
        assert truth["pose"]["pose"]["position"]["z"] == pytest.approx(0.1, abs=0.005)

        mover = Proc([str(BIN / "rostopic"), "pub", "-r", "20", "/probe/cmd_vel", "geometry_msgs/Twist",
                      "{linear: {x: 0.5}}"], sim.env, cwd=tmp_path)
        sim.procs.append(mover)
        wait_until(lambda: sim.echo("/probe/odom")["pose"]["pose"]["position"]["x"] > 0.3, timeout=30,
                   what="planar_move to carry the probe forward")
        odom = sim.echo("/probe/odom")
        assert (odom["header"]["frame_id"], odom["child_frame_id"]) == ("probe_odom", "probe")
        assert odom["pose"]["pose"]["position"]["y"] == pytest.approx(-2.0, abs=0.05)
        mover.stop()

        skid = Proc([str(BIN / "rostopic"), "pub", "-r", "20", "/skid/cmd_vel", "geometry_msgs/Twist",
                     "{linear: {x: 0.3}}"], sim.env, cwd=tmp_path)
        sim.procs.append(skid)
        wait_until(lambda: sim.echo("/skid/odom")["pose"]["pose"]["position"]["x"] > 0.3, timeout=30,
                   what="skid_steer_drive's four wheels to drive the rover forward")
        skid_odom = sim.echo("/skid/odom")
        assert (skid_odom["header"]["frame_id"], skid_odom["child_frame_id"]) == ("skid_odom", "skid_base")
        assert skid_odom["pose"]["pose"]["position"]["y"] == pytest.approx(2.0, abs=0.05)
        assert skid_odom["twist"]["twist"]["linear"]["x"] == pytest.approx(0.3, abs=0.05)
        skid.stop()

        info = sim.echo("/kinect/depth/camera_info")
        assert (info["width"], info["height"], info["header"]["frame_id"]) == (64, 48, "kinect_optical")
        depth = sim.run("rostopic", "echo", "-n", "1", "/kinect/depth/image_raw", timeout=30).stdout
        assert 'encoding: "32FC1"' in depth
        data = bytes(int(v) for v in depth.split("data: [")[1].split("]")[0].split(","))
        values = struct.unpack(f"<{64 * 48}f", data)
        centre = values[24 * 64 + 32]
        assert centre == pytest.approx(1.5, abs=0.02)  # the wall's face at x = 3, the head at 1.5
        points = sim.run("rostopic", "echo", "-n", "1", "--noarr", "/kinect/depth/points", timeout=30).stdout
        assert "width: 64" in points and "point_step: 16" in points
        assert "encoding" in sim.run("rostopic", "echo", "-n", "1", "--noarr", "/kinect/rgb/image_raw").stdout

        cloud = sim.echo("/head/cloud")
        assert len(cloud["points"]) == 27 and cloud["header"]["frame_id"] == "head"
        ahead = cloud["points"][13]  # the middle ray of the middle row
        assert math.dist((ahead["x"], ahead["y"], ahead["z"]), (1.5, 0.0, 0.0)) < 0.02
        assert launch.popen.poll() is None
