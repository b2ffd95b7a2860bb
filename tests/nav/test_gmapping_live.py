"""The course's mapping flow on the simulated TurtleBot: turtlebot_world.launch in the office,
`roslaunch turtlebot_gazebo gmapping_demo.launch` (slam_gmapping and move_base with
turtlebot_navigation's values), a drive down the corridor, then `rosrun map_server map_saver`
of the SLAM map; the map, its metadata, map -> odom, ~entropy and dynamic_map are gmapping's.
The saved map is scored with tests/nav/test_slam.py's metric and thresholds (tests/nav/mapscore.py;
that test holds a whole drive's map to them, on the world model)."""

from __future__ import annotations

import math
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image

from kame.nav.slam import MapView
from kame.node.node import Node, NodeConfig
from kame.stage.mapfile import load, parse_description
from tests.nav.mapscore import AGREEMENT, DRAWN_NEAR_WALLS, WALLS_DRAWN, score
from tests.nav.test_amcl_live import OFFICE, pose_of
from tests.nav.worlds import load_world_map
from tests.stage.sim import echo
from tests.support import Proc
from tests.turtlesim.sim import BIN, Sim, master


class _Driver:
    """The test's own node: /cmd_vel commanded from ground truth's callback, so the machine's load
    does not move where a leg ends (polled with rostopic echo, a loaded machine overshot the door
    by up to 1.5 m, the wall beside it then hiding the box in the south room, and the robot spun
    on through more turns, whose scans left walls misdrawn); gmapping's map times and entropy
    recorded as they arrive."""

    def __init__(self, sim: Sim) -> None:
        from geometry_msgs.msg import Twist
        from nav_msgs.msg import MapMetaData, Odometry
        from std_msgs.msg import Float64

        self.node = Node(NodeConfig("/driver", sim.uri, "127.0.0.1", "127.0.0.1"))
        self.command = self.node.advertise("/cmd_vel", Twist._type, Twist._md5sum, Twist._full_text)
        self.map_times: list[float] = []  # map_load_time of each /map_metadata
        self.entropies: list[float] = []
        self.leg: tuple[float, float, Callable[[Any], bool]] = (0.0, 0.0, lambda truth: True)
        self.ended, self.still = threading.Event(), threading.Event()
        self.lock = threading.Lock()
        self.node.subscribe("/map_metadata", MapMetaData._type, MapMetaData._md5sum, MapMetaData._full_text,
                            lambda frames, _: self.map_times.extend(
                                MapMetaData().deserialize(bytes(f)).map_load_time.to_sec() for f in frames))
        self.node.subscribe("/slam_gmapping/entropy", Float64._type, Float64._md5sum, Float64._full_text,
                            lambda frames, _: self.entropies.extend(
                                Float64().deserialize(bytes(f)).data for f in frames))

        def on_truth(frames: list[memoryview], header: dict[str, str]) -> None:
            truth = Odometry().deserialize(bytes(frames[-1]))
            go = Twist()
            with self.lock:  # a leg and its events change together
                linear, angular, until = self.leg
                if not self.ended.is_set() and until(truth):
                    self.ended.set()
                if not self.ended.is_set():
                    go.linear.x, go.angular.z = linear, angular
                elif truth.twist.twist.linear.x == truth.twist.twist.angular.z == 0.0:
                    self.still.set()
            self.command.publish_message(go)

        self.node.subscribe("/base_pose_ground_truth", Odometry._type, Odometry._md5sum, Odometry._full_text,
                            on_truth)

    def drive(self, linear: float, angular: float, until: Callable[[Any], bool], what: str) -> None:
        """Command (linear, angular) until `until(ground truth)`, then stop; returns once still."""
        with self.lock:
            self.ended.clear()
            self.still.clear()
            self.leg = (linear, angular, until)
        assert self.still.wait(90), f"{what} (ended: {self.ended.is_set()})"


def _yaw(truth: Any) -> float:
    q = truth.pose.pose.orientation
    return 2 * math.atan2(q.z, q.w)


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

        driver = _Driver(sim)
        try:
            driver.drive(0.4, 0.0, lambda truth: truth.pose.pose.position.x > 2.0,
                         "the robot to drive 2 m down the corridor, to a door")
            # then turn to face the south room through its door, and on until gmapping publishes a map
            # with what it saw facing south (a map at a processed scan map_update_interval, 5 s, after
            # the last)
            facing: list[float] = []

            def faced_south_and_mapped(truth: Any) -> bool:
                if not facing and _yaw(truth) <= -math.pi / 2:
                    facing.append(truth.header.stamp.to_sec())
                return bool(facing) and any(t > facing[0] for t in driver.map_times)

            driver.drive(0.0, -0.6, faced_south_and_mapped, "a map with what the robot saw facing south")
        finally:
            driver.node.shutdown("driven")
        assert driver.entropies  # after each processed scan: while it turns
        assert all(0 <= entropy <= math.log(80) + 1e-6 for entropy in driver.entropies)  # of 80 particles' weights
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
