"""The turtle_tf and turtle_tf2 demos as the courses run them (`roslaunch turtle_tf2
turtle_tf2_demo.launch`): turtle2 is spawned and chases turtle1 wherever it goes; the
tutorials' carrot frames hang off turtle1. Headless turtlesim (no display in tests)."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import pytest

from ..support import kame_command
from .graph import Graph

SHARE = Path(__file__).resolve().parents[2] / "src" / "kame" / "share"

CHASE = """
    import math, rospy
    from turtlesim.msg import Pose
    from turtlesim.srv import TeleportAbsolute
    rospy.init_node('judge')
    rospy.wait_for_service('/turtle1/teleport_absolute', 30)
    def distance_to(x, y):
        pose = rospy.wait_for_message('/turtle2/pose', Pose, 30)
        return math.hypot(pose.x - x, pose.y - y)
    # turtle2 first reaches turtle1 where it starts, then follows it to a new place
    for x, y in ((5.544445, 5.544445), (9.0, 2.0)):
        if (x, y) != (5.544445, 5.544445):
            rospy.ServiceProxy('/turtle1/teleport_absolute', TeleportAbsolute)(x, y, 0.0)
        deadline = rospy.Time.now() + rospy.Duration(40)
        while distance_to(x, y) > 0.6 and rospy.Time.now() < deadline:
            pass
        print('reached', x, y, distance_to(x, y) <= 0.6, flush=True)
"""


@pytest.mark.parametrize("launch", ["turtle_tf2_demo.launch", "turtle_tf_demo.launch", "turtle_tf2_demo_cpp.launch",
                                    "turtle_tf_demo_cpp.launch"])
def test_turtle2_chases_turtle1(graph: Graph, launch: str) -> None:
    roslaunch = graph.start(kame_command("kame.cli.roslaunch", launch.split("_demo")[0], launch))
    out = graph.finish(graph.kame(CHASE), timeout=120)
    assert out.splitlines() == ["reached 5.544445 5.544445 True", "reached 9.0 2.0 True"]
    # Ctrl-C ends the launch: every node stops on its SIGINT (none left for roslaunch to escalate)
    graph.procs.remove(roslaunch)
    _, err = roslaunch.stop(timeout=30)
    assert roslaunch.popen.returncode == 0 and "escalating" not in err, err


@pytest.mark.parametrize(("script", "radius", "fixed"), [
    ("turtle_tf2/nodes/fixed_tf2_broadcaster.py", 2.0, True), ("turtle_tf/nodes/fixed_tf_broadcaster.py", 2.0, True),
    ("turtle_tf2/nodes/dynamic_tf2_broadcaster.py", 10.0, False),
    ("turtle_tf/nodes/dynamic_tf_broadcaster.py", 2.0, False),
])
def test_carrot_frames(graph: Graph, script: str, radius: float, fixed: bool) -> None:
    """The carrot is 2 m left of turtle1 (fixed), or circles it (moving), as the tutorials write."""
    graph.start([sys.executable, str(SHARE / "turtle_tf2/nodes/turtle_tf2_broadcaster.py"), "_turtle:=turtle1"])
    graph.start(kame_command("kame.cli.rosrun", "turtlesim", "turtlesim_node", "--headless"))
    graph.start([sys.executable, str(SHARE / script)])
    out = graph.finish(graph.kame("""
        import math, rospy, tf2_ros
        rospy.init_node('carrot_check')
        buffer = tf2_ros.Buffer()
        tf2_ros.TransformListener(buffer)
        t = buffer.lookup_transform('world', 'carrot1', rospy.Time(0), rospy.Duration(20)).transform.translation
        c = buffer.lookup_transform('turtle1', 'carrot1', rospy.Time(0), rospy.Duration(20)).transform.translation
        print(round(t.x - 5.544445, 3), round(t.y - 5.544445, 3), round(math.hypot(c.x, c.y), 3))
    """), timeout=60)
    dx, dy, seen_radius = (float(v) for v in out.split())
    assert seen_radius == pytest.approx(radius, abs=1e-3)
    if fixed:  # turtle1 faces +x, so its frame is world's moved to (5.54, 5.54)
        assert (dx, dy) == pytest.approx((0.0, 2.0), abs=1e-3)
    else:  # through world, the carrot between two of its samples is interpolated along the chord
        assert radius * 0.95 < math.hypot(dx, dy) <= radius + 1e-3
