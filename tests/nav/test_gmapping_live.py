"""The course's mapping flow on the simulated TurtleBot: turtlebot_world.launch in the office,
`roslaunch turtlebot_gazebo gmapping_demo.launch` (slam_gmapping and move_base with
turtlebot_navigation's values), a drive down the corridor, then `rosrun map_server map_saver`
of the SLAM map; the map, its metadata, map -> odom, ~entropy and dynamic_map are gmapping's.
(The map's quality over a whole drive: tests/nav/test_slam.py, on the world model.)"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from PIL import Image

from kame.nav.slam import MapView
from kame.stage.mapfile import load, parse_description
from tests.nav.mapscore import AGREEMENT, DRAWN_NEAR_WALLS, WALLS_DRAWN, score
from tests.nav.test_amcl_live import OFFICE, pose_of
from tests.nav.worlds import load_world_map
from tests.stage.sim import echo
from tests.stage.test_stageros import drive
from tests.support import Proc
from tests.turtlesim.sim import BIN, master, wait_until


def _saved_view(yaml_path: Path) -> MapView:
    """map_saver's files read back as map_server reads them: 0 occupied, 254 free, 205 unknown."""
    description = parse_description(yaml_path.read_text())
    image = Path(description.image_path(str(yaml_path)))
    grid = load(description, image.read_bytes(), image.name)
    return MapView(grid.cells, grid.origin[:2], grid.resolution)


def test_gmapping_demo_maps_the_corridor_and_map_saver_keeps_it(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        world = Proc([str(BIN / "roslaunch"), "turtlebot_gazebo", "turtlebot_world.launch", f"world_file:={OFFICE}"],
                     sim.env, cwd=sim.home)
        sim.procs.append(world)
        world.wait_line("Simulating [robot_0]", timeout=30)
        demo = Proc([str(BIN / "roslaunch"), "turtlebot_gazebo", "gmapping_demo.launch"], sim.env, cwd=sim.home)
        sim.procs.append(demo)
        demo.wait_line("Initialization complete", timeout=60)
        first = echo(sim, "/map_metadata")
        assert abs(first["resolution"] - 0.05) < 1e-6  # a float32
        tf = echo(sim, "/tf", "--filter", "m.transforms[0].header.frame_id == 'map'")["transforms"][0]
        assert tf["child_frame_id"] == "odom"

        ahead = drive(sim, "/cmd_vel", 0.4)
        wait_until(lambda: pose_of(echo(sim, "/base_pose_ground_truth"))[0] > 2.0, timeout=60,
                   what="the robot to drive 2 m down the corridor, to a door")
        ahead.stop()
        turn = drive(sim, "/cmd_vel", 0.0, -0.6)  # to face the south room through its door, and on
        facing: dict[str, float] = {}

        def faces_south() -> bool:
            truth = echo(sim, "/base_pose_ground_truth")
            facing["stamp"] = truth["header"]["stamp"]["secs"] + truth["header"]["stamp"]["nsecs"] * 1e-9
            return abs(math.degrees(pose_of(truth)[2]) + 90) < 15

        wait_until(faces_south, timeout=60, what="the robot to face south")

        def map_time() -> float:
            stamp = echo(sim, "/map_metadata")["map_load_time"]
            return float(stamp["secs"] + stamp["nsecs"] * 1e-9)

        # gmapping publishes the map at a processed scan map_update_interval (5 s) after the last
        wait_until(lambda: map_time() > facing["stamp"], timeout=60, what="a map with what the robot saw facing south")
        entropy = echo(sim, "/slam_gmapping/entropy")["data"]  # after each processed scan: while it turns
        assert 0 <= entropy <= math.log(80) + 1e-6  # of 80 particles' weights
        turn.stop()
        call = sim.run("rosservice", "call", "/dynamic_map").stdout
        assert "frame_id: \"map\"" in call and "resolution: 0.05" in call

        saved = sim.run("rosrun", "map_server", "map_saver", "-f", str(tmp_path / "mymap")).stdout
        assert f"Writing map occupancy data to {tmp_path}/mymap.pgm" in saved and "Done" in saved
        description = (tmp_path / "mymap.yaml").read_text()
        origin = [float(v) for v in description.split("origin: [")[1].split("]")[0].split(",")]
        image = np.asarray(Image.open(tmp_path / "mymap.pgm"))[::-1]  # rows from the map's bottom
        resolution = 0.05

        def cell(x: float, y: float) -> int:
            return int(image[math.floor((y - origin[1]) / resolution), math.floor((x - origin[0]) / resolution)])

        # the corridor's walls, at y = -1 and +1 (their cells, 1 m long, between two doors), its
        # floor, and the top of the box in the south room (y = -4.2, x from 1 to 3) seen through
        # the door: map_saver's 0 occupied, 254 free, 205 unknown
        for y in (-1.025, 1.025):
            row = [min(cell(x, y + dy) for dy in (-0.05, 0.0, 0.05)) for x in np.arange(3.0, 4.5, 0.05)]
            assert sum(v == 0 for v in row) >= 0.8 * len(row), (y, row)
        floor = [cell(x, y) for x in np.arange(1.5, 4.0, 0.25) for y in (-0.5, 0.0, 0.5)]  # in the first scan's view
        assert all(v == 254 for v in floor), floor
        # (how much of it depends on which scans the turn's timing had processed: at least half)
        box = [min(cell(x, -4.225 + dy) for dy in (-0.1, -0.05, 0.0, 0.05, 0.1)) for x in np.arange(1.2, 2.8, 0.05)]
        assert sum(v == 0 for v in box) >= 0.5 * len(box), box
        assert cell(2.0, -3.0) == 254  # the room's floor before the box
        # the whole saved map against the world's, by the SLAM test's metric and thresholds
        found = score(_saved_view(tmp_path / "mymap.yaml"), load_world_map("office"))
        assert found.known > 6000, found  # the corridor's 2 m and what the turn saw of the rooms
        assert found.agreement >= AGREEMENT, found
        assert found.drawn_near_walls >= DRAWN_NEAR_WALLS, found
        assert found.walls_drawn >= WALLS_DRAWN, found
        demo.stop()
        assert demo.popen.returncode == 0


def test_turtlebot_navigation_launch_files_and_a_bad_parameter(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        bad = sim.run("rosrun", "gmapping", "slam_gmapping", "_particles:=0", check=False)
        assert bad.returncode == 1 and "particles must be at least 1" in bad.stdout + bad.stderr
        assert "Traceback" not in bad.stdout + bad.stderr
        world = Proc([str(BIN / "roslaunch"), "turtlebot_gazebo", "turtlebot_world.launch", f"world_file:={OFFICE}"],
                     sim.env, cwd=sim.home)
        sim.procs.append(world)
        world.wait_line("Simulating [robot_0]", timeout=30)
        amcl = Proc([str(BIN / "roslaunch"), "turtlebot_navigation", "amcl_demo.launch", f"map_file:={OFFICE}"],
                    sim.env, cwd=sim.home)
        sim.procs.append(amcl)
        found = pose_of(echo(sim, "/amcl_pose"))
        assert math.hypot(found[0], found[1]) < 0.5  # localised on the office's map, where it starts
        amcl.stop()
        assert amcl.popen.returncode == 0
        mapping = Proc([str(BIN / "roslaunch"), "turtlebot_navigation", "gmapping_demo.launch"], sim.env, cwd=sim.home)
        sim.procs.append(mapping)
        mapping.wait_line("Initialization complete", timeout=60)
        assert echo(sim, "/map", "--noarr")["header"]["frame_id"] == "map"
        assert "/move_base" in sim.run("rosnode", "list").stdout
        mapping.stop()
        assert mapping.popen.returncode == 0
