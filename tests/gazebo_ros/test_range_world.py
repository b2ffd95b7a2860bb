"""gazebo_ros's range_world.launch as the course runs it: gazebo_plugins' gazebo_ros_range.world,
its sonar reading the box in front of it; gui:=true's gzclient, without a display, says so in one line and the
server runs on."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.support import Proc
from tests.turtlesim.sim import BIN, master

# through kame.gazebo.engine, which chooses the headless renderer before MuJoCo loads (a bare `import
# mujoco` would fix its GL back end for every later test in this process)
pytest.importorskip("kame.gazebo.engine", reason="kame[gazebo] (MuJoCo) is not installed")


def test_the_sonar_reads_its_wall_and_gzclient_says_what_is_missing(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        launch = Proc([str(BIN / "roslaunch"), "gazebo_ros", "range_world.launch"], sim.env, cwd=tmp_path)
        sim.procs.append(launch)
        launch.wait_line("Finished loading Gazebo ROS API Plugin.", timeout=60)
        sonar = sim.echo("/sonar")
        assert sonar["header"]["frame_id"] == "sonar_link"
        assert (sonar["radiation_type"], sonar["field_of_view"], sonar["max_range"]) == (0, 0.5, 0.75)
        # model_2's near face is 0.475 m from model_1's centre, the sonar 0.25 m ahead of it
        assert sonar["range"] == pytest.approx(0.225, abs=0.005)
        sonar2 = sim.echo("/sonar2")
        assert sonar2["range"] > sonar2["max_range"]  # nothing in front of model_2: gazebo_ros_range's max float
        said = [line for line in launch.out + launch.err if "gzclient:" in line]
        assert len(said) == 1 and "gzserver keeps simulating" in said[0]  # no display in the tests
        assert launch.popen.poll() is None
        assert "model_1" in sim.run("rosservice", "call", "/gazebo/get_world_properties").stdout


def test_a_malformed_world_is_an_error_line_and_the_server_runs_on_empty(tmp_path: Path) -> None:
    broken = tmp_path / "broken.world"
    broken.write_text('<sdf version="1.6"><world name="w"><model name="m"><link name="l"></model></world></sdf>')
    with master(tmp_path) as sim:
        server = sim.start("gazebo_ros", "gzserver", str(broken), wait="Finished loading Gazebo ROS API Plugin.")
        errors = "".join(server.out + server.err)
        assert "broken.world" in errors and "runs on with an empty world" in errors
        assert "model_names: []" in sim.run("rosservice", "call", "/gazebo/get_world_properties").stdout
        assert "Traceback" not in errors
