"""`rosrun amcl amcl` on the TurtleBot in the office world (turtlebot_world.launch, map_server):
started from a wrong initial pose, it finds the robot while it drives; its topics, transform
and services are amcl's."""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.stage.sim import echo
from tests.stage.test_stageros import drive
from tests.support import Proc
from tests.turtlesim.sim import BIN, Sim, master, wait_until

OFFICE = str(Path(__file__).resolve().parents[2] / "src" / "kame" / "share" / "turtlebot_gazebo" / "worlds"
             / "office.yaml")


def pose_of(data: dict[str, Any]) -> tuple[float, float, float]:
    p, q = data["pose"]["pose"]["position"], data["pose"]["pose"]["orientation"]
    return p["x"], p["y"], 2 * math.atan2(q["z"], q["w"])


def drive_to(sim: Sim, x: float, speed: float, still: bool = True, timeout: float = 60) -> None:
    """Drive the robot forward at `speed` until its true x passes `x`, then stop it (and, with
    `still`, wait until its odometry says it stands)."""
    ahead = drive(sim, "/cmd_vel", speed)
    wait_until(lambda: pose_of(echo(sim, "/base_pose_ground_truth"))[0] > x, timeout=timeout,
               what=f"the robot to drive past x = {x} m")
    ahead.stop()
    if still:
        wait_until(lambda: echo(sim, "/odom")["twist"]["twist"]["linear"]["x"] == 0.0, timeout=20,
                   what="the robot to stop")


def error(sim: Sim) -> tuple[float, float]:
    found, truth = pose_of(echo(sim, "/amcl_pose")), pose_of(echo(sim, "/base_pose_ground_truth"))
    turn = math.remainder(found[2] - truth[2], 2 * math.pi)
    return math.hypot(found[0] - truth[0], found[1] - truth[1]), abs(math.degrees(turn))


def test_amcl_tracks_the_turtlebot_from_a_wrong_initial_pose(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        world = Proc([str(BIN / "roslaunch"), "turtlebot_gazebo", "turtlebot_world.launch", f"world_file:={OFFICE}"],
                     sim.env, cwd=sim.home)
        sim.procs.append(world)
        world.wait_line("Simulating [robot_0]", timeout=30)
        sim.start("map_server", "map_server", OFFICE, wait="Read a")
        amcl = sim.start("amcl", "amcl", "_base_frame_id:=base_footprint", "_initial_pose_x:=0.4",
                         "_initial_pose_y:=-0.3", "_initial_pose_a:=0.3", "_min_particles:=500",
                         "_max_particles:=2000", wait="Received a 320 X 240 map")
        first = pose_of(echo(sim, "/amcl_pose"))
        assert math.hypot(first[0] - 0.4, first[1] + 0.3) < 0.3  # it starts where it was told
        assert len(echo(sim, "/particlecloud")["poses"]) == 2000
        tf = echo(sim, "/tf", "--filter", "m.transforms[0].header.frame_id == 'map'")["transforms"][0]
        assert tf["child_frame_id"] == "odom"

        drive_to(sim, 1.5, 0.3, still=False)
        samples: list[tuple[float, float]] = []

        def found_the_robot() -> bool:
            samples.append(error(sim))
            distance, turn = samples[-1]
            return distance < 0.2 and turn < 10.0

        # both bounds in one sample (a tuple comparison would let the distance alone decide)
        try:
            wait_until(found_the_robot, timeout=30, what="amcl to find the robot")
        except AssertionError as exc:
            raise AssertionError(f"{exc}; the last (distance m, turn deg) seen: {samples[-5:]}") from None

        sim.run("rosservice", "call", "/global_localization")
        wait_until(lambda: len(echo(sim, "/particlecloud")["poses"]) == 2000, timeout=20,
                   what="the particles to spread")
        sim.run("rosservice", "call", "/request_nomotion_update")
        amcl.stop()
        assert amcl.popen.returncode == 0  # Ctrl-C ends it, no SIGKILL needed
        # a scan's callback still running as it shut down is no "bad callback" on the console
        assert not [line for line in amcl.out + amcl.err if "bad callback" in line or "Traceback" in line]


def test_a_laser_model_amcl_does_not_run_is_named_once_at_start_up(tmp_path: Path) -> None:
    """`beam` and `likelihood_field_prob` (amcl's other two models) run the likelihood field, and
    each amcl says so once, naming the value; the TurtleBot's likelihood_field says nothing."""
    with master(tmp_path) as sim:
        started = {model: sim.start("amcl", "amcl", f"__name:=amcl_{model}", f"_laser_model_type:={model}",
                                    wait="Requesting the map")  # past reading its parameters, no map served
                   for model in ("beam", "likelihood_field_prob", "likelihood_field")}
        for model, amcl in started.items():
            out, err = amcl.stop()  # all it printed, both streams read to their ends
            said = [line for line in (out + err).splitlines() if "laser_model_type" in line]
            if model == "likelihood_field":
                assert said == [], said
            else:
                assert len(said) == 1 and said[0].startswith("\033[33m[ WARN]") and said[0] in err, said
                assert f'"{model}" is not implemented here; using the likelihood_field model instead' in said[0], said


def test_an_initial_pose_must_be_in_the_map_frame_and_is_carried_forward_from_its_stamp(tmp_path: Path) -> None:
    """amcl's handleInitialPoseMessage: a pose in another frame is ignored with its warning; one
    stamped in the past has the odometry's motion since added (the robot at its start when the
    stamp was taken, then driven: the pose set is where it is now); one tf cannot place (a stamp
    in the future) is set as given, with a warning. The world runs at 0.4 times real time so that
    the stamp stays within the 10 s amcl's tf keeps, however slow the machine's tools are."""
    with master(tmp_path) as sim:
        sim.run("rosparam", "set", "/use_sim_time", "true")
        sim.start("stage_ros", "stageros", "-g", OFFICE, "base_scan:=scan", "_odom_drift_linear:=0.0",
                  "_odom_drift_angular:=0.0", "_real_time_factor:=0.4", wait="Simulating [robot_0]")
        sim.start("map_server", "map_server", OFFICE, wait="Read a")
        amcl = sim.start("amcl", "amcl", "_base_frame_id:=base_footprint", wait="Received a 320 X 240 map")
        echo(sim, "/tf", "--filter", "m.transforms[0].header.frame_id == 'map'")  # amcl has sent its transform
        at_start = echo(sim, "/odom")
        assert pose_of(at_start) == (0.0, 0.0, 0.0)
        stamp = at_start["header"]["stamp"]

        def set_pose(frame: str, secs: int, nsecs: int, x: float) -> None:
            sim.run("rostopic", "pub", "-1", "/initialpose", "geometry_msgs/PoseWithCovarianceStamped",
                    f"{{header: {{stamp: {{secs: {secs}, nsecs: {nsecs}}}, frame_id: '{frame}'}}, "
                    f"pose: {{pose: {{position: {{x: {x}}}, orientation: {{w: 1.0}}}}, "
                    f"covariance: [0.01, 0, 0, 0, 0, 0, 0, 0.01, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, "
                    f"0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.01]}}}}")

        def said(text: str) -> list[str]:  # amcl's lines without roscpp's colour codes
            return [re.sub(r"\x1b\[[0-9;]*m", "", line) for line in amcl.out + amcl.err if text in line]

        set_pose("odom", 0, 0, 3.0)
        wait_until(lambda: said('Ignoring initial pose in frame "odom"; initial poses must be in the global '
                                'frame, "map"'), what="amcl to refuse a pose in odom")
        assert not said("Setting pose")
        drive_to(sim, 0.5, 0.5, timeout=30)
        now = pose_of(echo(sim, "/base_pose_ground_truth"))
        set_pose("/map", stamp["secs"], stamp["nsecs"], 0.0)  # where the robot was at that stamp
        wait_until(lambda: said("Setting pose"), what="amcl to set the pose")
        x, y, yaw = (float(v) for v in said("Setting pose")[0].split(":")[-1].split())
        assert (x, y, yaw) == pytest.approx(now, abs=0.002)  # exact odometry: the truth, to the printed mm

        set_pose("map", stamp["secs"] + 1000, 0, 0.5)
        wait_until(lambda: said("Failed to transform initial pose in time"), what="amcl to say tf cannot place it")
        wait_until(lambda: len(said("Setting pose")) == 2, what="amcl to set the pose as given")
        assert said("Setting pose")[1].split(":")[-1].split() == ["0.500", "0.000", "0.000"]


def amcl_params(sim: Sim) -> dict[str, Any]:
    found = yaml.safe_load(sim.run("rosparam", "get", "/amcl").stdout)
    assert isinstance(found, dict)
    return found


def office_with_stage(sim: Sim) -> None:
    sim.start("stage_ros", "stageros", "-g", OFFICE, "base_scan:=scan", wait="Simulating [robot_0]")


def test_an_initial_pose_sent_before_the_map_is_set_once_the_map_is_here(tmp_path: Path) -> None:
    """amcl's initial_pose_hyp_: a pose that comes while amcl asks for static_map is kept, and the
    map's arrival places the particles there rather than at ~initial_pose_* (here the robot's true
    start, so that only the kept pose can put the estimate half a metre away)."""
    with master(tmp_path) as sim:
        office_with_stage(sim)
        amcl = sim.start("amcl", "amcl", "_base_frame_id:=base_footprint", wait="Requesting the map")
        sim.run("rostopic", "pub", "-1", "/initialpose", "geometry_msgs/PoseWithCovarianceStamped",
                "{header: {frame_id: map}, pose: {pose: {position: {x: 0.5, y: 0.3}, orientation: {w: 1.0}}, "
                "covariance: [0.0025, 0, 0, 0, 0, 0, 0, 0.0025, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, "
                "0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.0025]}}")
        amcl.wait_line("Setting pose")
        # no static_map yet: amcl asks again every 0.5 s, warning (on stderr) each time
        wait_until(lambda: sum("Request for map failed; trying again..." in line for line in amcl.err) >= 2,
                   what="amcl's warnings while static_map is missing")
        sim.start("map_server", "map_server", OFFICE, wait="Read a")
        amcl.wait_line("Received a 320 X 240 map")
        x, y, yaw = pose_of(echo(sim, "/amcl_pose"))  # the forced first update's, latched
        assert math.hypot(x - 0.5, y - 0.3) < 0.15 and abs(yaw) < 0.15, (x, y, yaw)


def test_amcl_saves_its_pose_for_a_restart_every_2_s_and_on_ctrl_c(tmp_path: Path) -> None:
    """~save_pose_rate (0.5 Hz by default): amcl writes its pose and variances to ~initial_pose_*
    and ~initial_cov_*; an amcl started again begins there. With the rate at -1 only Ctrl-C saves."""
    with master(tmp_path) as sim:
        office_with_stage(sim)
        sim.start("map_server", "map_server", OFFICE, wait="Read a")
        amcl = sim.start("amcl", "amcl", "_base_frame_id:=base_footprint", "_initial_pose_x:=0.4",
                         "_initial_pose_y:=-0.3", "_initial_pose_a:=0.3", wait="Received a 320 X 240 map")
        drive_to(sim, 1.0, 0.3)
        # an update where the robot stands: amcl_pose is then the pose amcl saves there
        sim.run("rosservice", "call", "/request_nomotion_update")
        seen: list[tuple[Any, Any]] = []

        def saved_what_it_published() -> bool:
            published, saved = echo(sim, "/amcl_pose"), amcl_params(sim)
            seen.append((pose_of(published), saved))
            return (saved["initial_pose_x"], saved["initial_pose_y"], saved["initial_pose_a"]) \
                == pytest.approx(pose_of(published), abs=1e-3) \
                and (saved["initial_cov_xx"], saved["initial_cov_yy"], saved["initial_cov_aa"]) \
                == pytest.approx([published["pose"]["covariance"][i] for i in (0, 7, 35)], rel=1e-6)

        try:
            wait_until(saved_what_it_published, timeout=30, what="amcl to save the pose it published")
        except AssertionError as exc:
            raise AssertionError(f"{exc}; last seen: {seen[-2:]}") from None
        amcl.stop()
        assert amcl.popen.returncode == 0
        # read after the stop: its Ctrl-C save is its last word (an update between a read before the
        # stop and the stop moved the saved pose, seen beside two suites)
        saved = amcl_params(sim)
        assert saved["initial_pose_x"] > 1.0

        again = sim.start("amcl", "amcl", "_base_frame_id:=base_footprint", "_save_pose_rate:=-1.0",
                          wait="Received a 320 X 240 map")
        x, y, _ = pose_of(echo(sim, "/amcl_pose"))
        assert math.hypot(x - saved["initial_pose_x"], y - saved["initial_pose_y"]) < 0.2, (x, y, saved)
        # past the saved pose, wherever the first drive stopped (each look at the ground truth takes a
        # rostopic's start-up, so under load the robot runs on past its mark)
        drive_to(sim, saved["initial_pose_x"] + 0.6, 0.3)
        # scans go on arriving; with no rate, nothing was written since the restart
        assert {k: v for k, v in amcl_params(sim).items() if k.startswith("initial_")} == \
            {k: v for k, v in saved.items() if k.startswith("initial_")}
        again.stop()
        assert again.popen.returncode == 0
        assert amcl_params(sim)["initial_pose_x"] > saved["initial_pose_x"] + 0.4  # Ctrl-C saved it
