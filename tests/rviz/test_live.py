"""rviz on a live graph: the turtle_tf2 demo's frames moving in the TF display (turtle2 chasing
turtle1, turtle1 teleported), a MarkerArray from a script drawn, and the Publish Point tool's
click arriving on /clicked_point. The window runs in its own process on a private Xvfb."""

from __future__ import annotations

import signal
import sys
import time
import xmlrpc.client
from pathlib import Path

import pytest

from tests.support import REPO, Proc, kame_command
from tests.tf.graph import Graph

pytest.importorskip("OpenGL", reason="rviz draws through PyOpenGL (pip install 'kame[gui]')")
pytest.importorskip("PySide6")

RVIZ_FILE = """\
Visualization Manager:
  Displays:
    - Class: rviz/TF
      Enabled: true
      Name: TF
    - Class: rviz/MarkerArray
      Enabled: true
      Name: Markers
      Marker Topic: /markers
      Topic: /markers
  Global Options:
    Background Color: 48; 48; 48
    Fixed Frame: world
    Frame Rate: 30
  Views:
    Current:
      Class: rviz/TopDownOrtho
      Scale: 40
      X: 5.5
      Y: 5.5
"""

MARKERS = """
    import rospy
    from visualization_msgs.msg import Marker, MarkerArray
    rospy.init_node('markers')
    pub = rospy.Publisher('/markers', MarkerArray, queue_size=1, latch=True)
    marker = Marker(ns='test', id=1, type=Marker.CUBE)
    marker.header.frame_id = 'world'
    marker.pose.position.x = marker.pose.position.y = 2.0
    marker.pose.orientation.w = 1.0
    marker.scale.x = marker.scale.y = marker.scale.z = 0.5
    marker.color.g = marker.color.a = 1.0
    pub.publish(MarkerArray(markers=[marker]))
    rospy.spin()
"""

CLICKED = """
    import rospy
    from geometry_msgs.msg import PointStamped
    rospy.init_node('clicked')
    point = rospy.wait_for_message('/clicked_point', PointStamped, 60)
    print(point.header.frame_id, round(point.point.x, 1), round(point.point.y, 1), flush=True)
"""


def _frames(line: str) -> dict[str, tuple[float, float, str]]:
    found = {}
    for part in line.split()[1:]:
        if part == "status":
            break
        name, _, value = part.partition("=")
        if value != "none":
            x, y, drawn = value.split(",")
            found[name] = (float(x), float(y), drawn)
    return found


def _next_report(rviz: Proc, after: int, timeout: float = 60.0) -> tuple[int, str]:
    """The first report line from line number `after` on: (its number, the line)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        lines = [line for line in list(rviz.out) if line.startswith("frames ")]
        if len(lines) > after:
            return after + 1, lines[after]
        time.sleep(0.05)
    raise AssertionError(f"no report from rviz:\n{''.join(rviz.out)}\n{''.join(rviz.err)}")


def test_the_turtle_tf_demo_frames_move_markers_show_and_a_click_is_published(tmp_path: Path) -> None:
    from tests.turtlesim.xserver import xvfb

    graph = Graph(tmp_path)
    try:
        rviz_file = tmp_path / "demo.rviz"
        rviz_file.write_text(RVIZ_FILE)
        graph.start(kame_command("kame.cli.roslaunch", "turtle_tf2", "turtle_tf2_demo.launch"))
        graph.kame(MARKERS)
        clicked = graph.kame(CLICKED)
        with xvfb() as display:
            env = {k: v for k, v in graph.env.items() if k not in ("WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
            rviz = Proc([sys.executable, "-m", "tests.rviz.live_child", graph.uri, str(rviz_file),
                         "world", "turtle1", "turtle2", "--click", "3,7"], dict(env, DISPLAY=display), cwd=REPO)
            graph.procs.append(rviz)
            seen, line = 0, ""
            deadline = time.monotonic() + 90
            while time.monotonic() < deadline:  # both turtles' frames appear in the window, drawn
                seen, line = _next_report(rviz, seen)
                frames = _frames(line)
                if {"turtle1", "turtle2"} <= set(frames) and "Markers:Ok" in line:
                    break
            assert {"turtle1", "turtle2"} <= set(frames) and "Markers:Ok" in line, line
            assert frames["turtle1"][:2] == pytest.approx((5.544, 5.544), abs=0.01)
            assert frames["turtle1"][2] == frames["turtle2"][2] == "drawn", line
            start2 = frames["turtle2"][:2]
            out = graph.finish(clicked, timeout=60)
            assert out.split() == ["world", "3.0", "7.0"]
            graph.finish(graph.kame("""
                import rospy
                from turtlesim.srv import TeleportAbsolute
                rospy.init_node('mover')
                rospy.wait_for_service('/turtle1/teleport_absolute', 30)
                rospy.ServiceProxy('/turtle1/teleport_absolute', TeleportAbsolute)(9.0, 2.0, 0.0)
            """))
            deadline = time.monotonic() + 90
            moved = 0.0
            while time.monotonic() < deadline:  # turtle1 is where it was teleported; turtle2 moves after it
                seen, line = _next_report(rviz, seen)
                frames = _frames(line)
                moved = abs(frames["turtle2"][0] - start2[0]) + abs(frames["turtle2"][1] - start2[1])
                if frames["turtle1"][:2] == pytest.approx((9.0, 2.0), abs=0.01) and moved > 0.5:
                    break
            assert frames["turtle1"][:2] == pytest.approx((9.0, 2.0), abs=0.01) and moved > 0.5, line
    finally:
        graph.stop()


def test_rviz_and_rosrun_rviz_rviz_start_and_refuse_a_bad_config(tmp_path: Path) -> None:
    import subprocess

    from tests.support import ros_env
    from tests.turtlesim.sim import BIN

    env = ros_env(tmp_path)
    for command in ([str(BIN / "rviz"), "--help"], [str(BIN / "rosrun"), "rviz", "rviz", "--help"]):
        helped = subprocess.run(command, capture_output=True, text=True, timeout=60, env=env)
        assert helped.returncode == 0 and "--display-config" in helped.stdout, (command, helped.stderr)
    bad = tmp_path / "bad.rviz"
    bad.write_text("- not: a mapping\n")
    refused = subprocess.run([str(BIN / "rviz"), "-d", str(bad)], capture_output=True, text=True, timeout=60, env=env)
    assert refused.returncode == 1 and "cannot load" in refused.stderr and "a YAML mapping" in refused.stderr


STAMPED_MARKERS = """
    import rospy, tf2_ros
    from geometry_msgs.msg import TransformStamped
    from visualization_msgs.msg import Marker, MarkerArray
    rospy.init_node('stamped_markers')
    world = TransformStamped()
    world.header.frame_id, world.child_frame_id = 'world', 'base'
    world.transform.rotation.w = 1.0
    tf2_ros.StaticTransformBroadcaster().sendTransform(world)
    pub = rospy.Publisher('/markers', MarkerArray, queue_size=1)
    marker = Marker(ns='test', id=1, type=Marker.CUBE)
    marker.header.frame_id = 'world'
    marker.pose.orientation.w = 1.0
    marker.scale.x = marker.scale.y = marker.scale.z = 0.5
    marker.color.g = marker.color.a = 1.0
    rate = rospy.Rate(5)
    while not rospy.is_shutdown():
        marker.header.stamp = rospy.Time.now()
        marker.pose.position.x = (marker.pose.position.x + 1.0) % 10  # a new place: a new frame to swap
        pub.publish(MarkerArray(markers=[marker]))
        rate.sleep()
"""


def test_rviz_stats_log_each_message_when_its_frame_reaches_the_screen(tmp_path: Path) -> None:
    """KAME_RVIZ_STATS in the real `rviz` on Xvfb: a line for each stamped MarkerArray drawn, written
    after its frame's buffer swap (what bench/rviz_e2e_bench.py measures latency by)."""
    from tests.turtlesim.sim import BIN
    from tests.turtlesim.xserver import xvfb

    graph = Graph(tmp_path)
    try:
        rviz_file, shown = tmp_path / "stats.rviz", tmp_path / "shown"
        rviz_file.write_text(RVIZ_FILE)
        graph.kame(STAMPED_MARKERS)
        with xvfb() as display:
            env = {k: v for k, v in graph.env.items() if k not in ("WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
            rviz = Proc([str(BIN / "rviz"), "-d", str(rviz_file)],
                        dict(env, DISPLAY=display, KAME_RVIZ_STATS=str(shown)), cwd=tmp_path)
            graph.procs.append(rviz)
            deadline = time.monotonic() + 90
            while time.monotonic() < deadline and len(shown.read_text().splitlines() if shown.exists() else []) < 3:
                assert rviz.popen.poll() is None, "".join(rviz.err)
                time.sleep(0.05)
            rows = [line.split() for line in shown.read_text().splitlines()]
            assert len(rows) >= 3, "".join(rviz.err)
            stamps = [float(stamp) for _, stamp, _, _ in rows]
            assert {topic for topic, _, _, _ in rows} == {"/markers"} and stamps == sorted(set(stamps))
            for _, stamp, taken, swapped in rows:  # one clock on one host: published, taken, then on the screen
                assert float(stamp) <= float(taken) <= float(swapped) < float(stamp) + 60
    finally:
        graph.stop()


@pytest.mark.parametrize("how", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_rviz_ends_on_ctrl_c_and_sigterm_and_leaves_the_master(tmp_path: Path, how: signal.Signals) -> None:
    """rviz on Xvfb, drawing (its --stats lines come), ends on SIGINT or SIGTERM as its window's
    close does: exit 0, and its node's subscriptions gone from the master (a killed rviz left a
    dead node in rosnode list and rqt_graph)."""
    from tests.turtlesim.sim import BIN
    from tests.turtlesim.xserver import xvfb

    graph = Graph(tmp_path)
    try:
        rviz_file = tmp_path / "quit.rviz"
        rviz_file.write_text(RVIZ_FILE)
        with xvfb() as display:
            env = {k: v for k, v in graph.env.items() if k not in ("WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
            rviz = Proc([str(BIN / "rviz"), "-d", str(rviz_file), "--stats", "__name:=rviz_quit"],
                        dict(env, DISPLAY=display), cwd=tmp_path)
            graph.procs.append(rviz)
            rviz.wait_line("rviz stats:", timeout=90)
            master = xmlrpc.client.ServerProxy(graph.uri)

            def subscribed() -> set[str]:
                return {topic for topic, nodes in master.getSystemState("/test")[2][1] if "/rviz_quit" in nodes}

            assert "/tf" in subscribed()
            rviz.popen.send_signal(how)
            assert rviz.popen.wait(30) == 0, "".join(rviz.err)
            assert "Traceback" not in "".join(rviz.err)
            assert subscribed() == set()
    finally:
        graph.stop()
