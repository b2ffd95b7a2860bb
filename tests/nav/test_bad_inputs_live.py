"""amcl and move_base given what they cannot use, as a careless user or a broken driver sends it:
each input is one line saying what is wrong, and the node goes on serving (no traceback)."""

from __future__ import annotations

import sys
import textwrap
from pathlib import Path

from tests.nav.test_amcl_live import OFFICE
from tests.support import Proc
from tests.turtlesim.sim import master, wait_until


def stderr_line(proc: Proc, text: str) -> str:
    """The first stderr line of `proc` containing `text`, waiting for it."""
    def found() -> list[str]:
        return [line for line in list(proc.err) if text in line]

    wait_until(lambda: bool(found()), timeout=30, what=f"{text!r} on stderr:\n{''.join(proc.err)}")
    return found()[0]


def test_amcl_refuses_an_empty_map_nan_poses_and_scans_and_goes_on_serving(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        amcl = sim.start("amcl", "amcl", "_use_map_topic:=true", wait="Subscribed to map topic.")
        sim.run("rostopic", "pub", "-1", "/map", "nav_msgs/OccupancyGrid", "{}")
        assert "Ignoring the map: the map is 0 x 0 cells: there is no cell to localise or plan on; amcl is " \
               "waiting for a usable map" in stderr_line(amcl, "Ignoring the map")
        sim.run("rosservice", "call", "/global_localization")  # it used to answer with a traceback
        stderr_line(amcl, "global_localization: there is no map yet to spread the particles over")
        sim.run("rostopic", "pub", "-1", "/initialpose", "geometry_msgs/PoseWithCovarianceStamped",
                "{header: {frame_id: map}, pose: {pose: {position: {x: .nan}, orientation: {w: 1}}}}")
        assert "Position (nan, 0, 0) has nans or infs" in stderr_line(amcl, "Ignoring initial pose")
        sim.run("rostopic", "pub", "-1", "/scan", "sensor_msgs/LaserScan",
                "{header: {frame_id: laser}, angle_increment: .nan, range_max: 10, ranges: [1, 2]}")
        assert "its angle_min and angle_increment (0, nan) are not finite" in stderr_line(amcl, "Ignoring a scan")
        sim.run("rosservice", "call", "/request_nomotion_update")  # still serving
        amcl.stop()
        assert amcl.popen.returncode == 0 and "Traceback" not in "".join(amcl.err), "".join(amcl.err)


def test_slam_gmapping_leaves_out_a_scan_it_cannot_place(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        gmapping = sim.start("gmapping", "slam_gmapping")
        wait_until(lambda: "/slam_gmapping" in sim.run("rostopic", "info", "/scan", check=False).stdout, timeout=30,
                   what="slam_gmapping to subscribe to /scan")
        sim.run("rostopic", "pub", "-1", "/scan", "sensor_msgs/LaserScan",
                "{header: {frame_id: laser}, angle_increment: 0.1, range_max: .inf, ranges: [1, 2]}")
        assert "its range_max is inf: the map's beams need a length" in stderr_line(gmapping, "Ignoring a scan")
        gmapping.stop()
        assert "Traceback" not in "".join(gmapping.err), "".join(gmapping.err)


GOALS = """
    import actionlib, rospy, sys
    from move_base_msgs.msg import MoveBaseAction, MoveBaseGoal
    rospy.init_node("careless_client")
    client = actionlib.SimpleActionClient("move_base", MoveBaseAction)
    client.wait_for_server()
    for x, y, qz, qw in [(float("nan"), 0, 0, 1), (float("inf"), 0, 0, 1), (1, 0, 0, 0), (0, 0, float("nan"), 1),
                         (1000, 0, 0, 1)]:
        goal = MoveBaseGoal()
        goal.target_pose.header.frame_id = "map"
        goal.target_pose.pose.position.x, goal.target_pose.pose.position.y = x, y
        goal.target_pose.pose.orientation.z, goal.target_pose.pose.orientation.w = qz, qw
        client.send_goal(goal)
        client.wait_for_result()
        print("state", client.get_state(), client.get_goal_status_text(), flush=True)
"""


def test_move_base_aborts_nan_and_off_map_goals_with_the_reason(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        sim.start("map_server", "map_server", OFFICE, wait="Read a")
        move_base = sim.start("move_base", "move_base")
        client = Proc([sys.executable, "-c", textwrap.dedent(GOALS)], sim.env, cwd=sim.home)
        sim.procs.append(client)
        wait_until(lambda: sum(line.startswith("state") for line in client.out) == 5, timeout=60,
                   what=f"five goals' results:\n{''.join(client.out)}{''.join(client.err)}")
        states = [line.strip() for line in client.out if line.startswith("state")]
        nan_position = "state 4 Aborting on goal because it was sent with a position that has nans or infs"
        bad_quaternion = "state 4 Aborting on goal because it was sent with an invalid quaternion"
        assert states[:4] == [nan_position, nan_position, bad_quaternion, bad_quaternion], states
        assert states[4].startswith("state 4 Aborting on goal because it is off the global costmap: (1000, 0) is "
                                    "outside [-"), states
        errors = "".join(move_base.err)
        assert "Position (nan, 0, 0) has nans or infs... discarding as a navigation goal" in errors
        assert "Quaternion has length close to zero... discarding as navigation goal" in errors
        assert "The goal sent to the navfn planner is off the global costmap." in errors
        sim.run("rosservice", "call", "/move_base/clear_costmaps")  # still serving
        move_base.stop()
        assert "Traceback" not in "".join(move_base.err), "".join(move_base.err)
