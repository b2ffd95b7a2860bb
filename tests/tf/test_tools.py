"""kame's tf tools as a user runs them, side by side with Debian's: static_transform_publisher
(tf2_ros's once-latched form and tf's periodic form), tf_echo and tf2_tools' echo.py. Every
process is stopped by its PID."""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

import pytest

from ..support import SYSTEM_PYTHON, Proc, kame_command
from .graph import DEBIAN_STATIC, DEBIAN_TF_ECHO, Graph, debian

DEBIAN_TF_STATIC = "/usr/lib/tf/static_transform_publisher"


def kame_tool(module: str, function: str, *args: str) -> list[str]:
    return [sys.executable, "-c", f"import sys; from {module} import {function}; sys.exit({function}())", *args]


STATIC_TF2 = kame_tool("kame.cli.static_transform_publisher", "main_tf2")
STATIC_TF = kame_tool("kame.cli.static_transform_publisher", "main_tf")
TF_ECHO = kame_command("kame.cli.tf_echo")
TF2_ECHO = kame_tool("kame.cli.tf_echo", "main_tf2")


def echoed(proc_out: list[str], count: int = 2) -> list[str]:
    """The first `count` echoes without their 'At time' lines."""
    blocks = "".join(proc_out).split("At time ")[1:]
    return ["\n".join(block.splitlines()[1:]) for block in blocks[:count]]


@debian
@pytest.mark.parametrize(("ours", "theirs", "args"), [
    (STATIC_TF2, [DEBIAN_STATIC], ["1", "2"]),
    (STATIC_TF, [DEBIAN_TF_STATIC], ["1", "2", "3"]),
    (TF_ECHO, [DEBIAN_TF_ECHO], ["only_one"]),
], ids=["tf2_static", "tf_static", "tf_echo"])
def test_usage_is_debians(graph: Graph, ours: list[str], theirs: list[str], args: list[str]) -> None:
    mine = subprocess.run([*ours, *args], env=graph.env, capture_output=True, text=True, timeout=30)
    real = subprocess.run([*theirs, *args], env=graph.env, capture_output=True, text=True, timeout=30)
    assert (mine.stdout, mine.returncode) == (real.stdout, real.returncode)


@debian
def test_tf_echo_prints_what_debians_prints(graph: Graph) -> None:
    # kame's and Debian's publishers, each form, in one tree: world -> base -> arm -> hand
    graph.start([*STATIC_TF2, "1", "2", "3", "0.1", "0.2", "0.3", "world", "base"])
    graph.start([*STATIC_TF, "0", "0", "0.5", "0", "0", "0.3826834", "0.9238795", "base", "arm", "50"])
    graph.start([DEBIAN_STATIC, "0.25", "0", "0", "0", "0", "0", "1", "arm", "hand"])
    ours = graph.start([*TF_ECHO, "world", "hand", "5"])
    theirs = graph.start([DEBIAN_TF_ECHO, "world", "hand", "5"])
    for proc in (ours, theirs):
        proc.wait_line("- Translation", timeout=20)
    ours.wait_line("in RPY (degree)")
    theirs.wait_line("in RPY (degree)")
    assert echoed(ours.out, 1) == echoed(theirs.out, 1)
    assert echoed(ours.out, 1)[0].startswith("- Translation: [")
    static_only = graph.start([*TF_ECHO, "base", "world"])
    static_only.wait_line("At time 0.000")


@debian
def test_echo_py_and_missing_frames(graph: Graph) -> None:
    graph.start([*STATIC_TF2, "1", "0", "0", "0", "0", "0", "1", "map", "odom"])
    graph.start([*STATIC_TF, "0", "0", "0", "0.3", "0.2", "0.1", "odom", "base", "100"])
    # two nodes named /echo would shut each other down, as ROS does: ours gets another name
    echo = graph.start([*TF2_ECHO, "map", "base", "-r", "5", "-l", "50", "__name:=kame_echo"])
    real = graph.start([SYSTEM_PYTHON, "/usr/lib/tf2_tools/echo.py", "map", "base", "-r", "5", "-l", "50"])
    for proc in (echo, real):
        proc.wait_line("- Translation: [1.000, 0.000, 0.000]", timeout=20)
        proc.wait_line("in RPY (degree)")
    assert echoed(echo.out, 1) == echoed(real.out, 1)
    missing = graph.start([*TF_ECHO, "map", "ghost"])
    missing.wait_line('Exception thrown:"ghost" passed to lookupTransform argument source_frame does not exist. ')
    missing.wait_line("Frame odom exists with parent map.")


def test_the_programs_are_in_their_packages() -> None:
    share = Path(__file__).resolve().parents[2] / "src" / "kame" / "share"
    for program in ("tf2_ros/nodes/static_transform_publisher", "tf/nodes/static_transform_publisher",
                    "tf/nodes/tf_echo", "tf/nodes/tf_monitor", "tf/nodes/view_frames", "tf2_tools/scripts/echo.py",
                    "tf2_tools/scripts/view_frames.py", "turtle_tf/nodes/turtle_tf_broadcaster",
                    "turtle_tf/nodes/turtle_tf_listener"):
        path = share / program
        assert path.stat().st_mode & 0o111, program
        compile(path.read_text(), str(path), "exec")  # a syntax error fails here


def pdf_is_well_formed(data: bytes) -> bool:
    """Header, trailer, and every xref offset pointing at its object."""
    if not data.startswith(b"%PDF-1.4\n") or not data.rstrip().endswith(b"%%EOF"):
        return False
    start = int(data.rsplit(b"startxref\n", 1)[1].split()[0])
    rows = data[start:].split(b"\n")
    count = int(rows[1].split()[1])
    offsets = [int(row.split()[0]) for row in rows[3:2 + count]]
    return all(data[offset:].startswith(b"%d 0 obj" % number) for number, offset in enumerate(offsets, start=1))


@pytest.mark.parametrize(("function", "first_line"), [("main_tf", "digraph G {"), ("main_tf2", "digraph G {")])
def test_view_frames_writes_gv_and_pdf(graph: Graph, tmp_path: Path, function: str, first_line: str) -> None:
    publishers = [graph.start([*STATIC_TF2, "1", "0", "0", "0", "0", "0", "world", "base"]),
                  graph.start([*STATIC_TF, "0", "1", "0", "0", "0", "0", "base", "(camera)", "100"])]
    graph.wait_for_publishers("/tf", "/tf_static")  # view_frames listens 5 s: a publisher still starting misses it
    here = tmp_path / "out"
    here.mkdir()
    proc = Proc(kame_tool("kame.cli.view_frames", function), graph.env, cwd=here)
    graph.procs.append(proc)
    out = graph.finish(proc, timeout=40)
    dot = (here / "frames.gv").read_text()
    assert dot.splitlines()[0] == first_line
    heard = [(p.popen.poll(), "".join(p.out), "".join(p.err)) for p in publishers]
    assert '"world" -> "base"' in dot and '"base" -> "(camera)"' in dot, f"{dot}\n{out}\npublishers: {heard}"
    assert "view_frames Result" in dot
    pdf = (here / "frames.pdf").read_bytes()
    assert pdf_is_well_formed(pdf)
    assert b"(\\(camera\\)) Tj" in pdf and b"(world) Tj" in pdf  # names drawn, PDF-escaped


TF_LISTENER_NODE = """
    import rospy, tf
    rospy.init_node('looker')
    listener = tf.TransformListener()
    listener.waitForTransform('world', 'base', rospy.Time(0), rospy.Duration(30))
    print('ready', flush=True)
    rospy.spin()
"""


def test_view_frames_node_asks_one_listeners_tf_frames(graph: Graph, tmp_path: Path) -> None:
    graph.start([*STATIC_TF2, "1", "0", "0", "0", "0", "0", "world", "base"])
    looker = graph.kame(TF_LISTENER_NODE)
    looker.wait_line("ready", timeout=40)
    proc = Proc(kame_tool("kame.cli.view_frames", "main_tf", "--node=looker"), graph.env, cwd=tmp_path)
    graph.procs.append(proc)
    out = graph.finish(proc, timeout=40)
    assert out.splitlines() == ["Generating graph for node:  looker", "Waiting for service /looker/tf_frames",
                                "Polling service", "frames.pdf generated"]
    dot = (tmp_path / "frames.gv").read_text()
    assert dot.startswith("digraph G {") and '"world" -> "base"[label="Broadcaster: /static_transform_publisher' in dot
    assert b"(world) Tj" in (tmp_path / "frames.pdf").read_bytes()


@debian
def test_debians_view_frames_node_reads_a_kame_listener(graph: Graph, tmp_path: Path) -> None:
    graph.start([*STATIC_TF2, "1", "0", "0", "0", "0", "0", "world", "base"])
    looker = graph.kame(TF_LISTENER_NODE)
    looker.wait_line("ready", timeout=40)
    # Debian's writes frames.gv, then stops where it would run graphviz's dot (absent or not)
    proc = Proc([SYSTEM_PYTHON, "/usr/lib/tf/view_frames", "--node=/looker"], graph.env, cwd=tmp_path)
    graph.procs.append(proc)
    try:
        proc.popen.wait(40)
    except subprocess.TimeoutExpired:
        pass
    proc.stop()
    assert '"world" -> "base"[label="Broadcaster: /static_transform_publisher' in (tmp_path / "frames.gv").read_text()


def test_tf_monitor_reports_frames_broadcasters_and_a_chain(graph: Graph) -> None:
    graph.start([*STATIC_TF2, "1", "0", "0", "0", "0", "0", "world", "base", "__name:=fixed"])
    graph.start([*STATIC_TF, "0", "1", "0", "0", "0", "0", "base", "camera", "100", "__name:=moving"])
    monitor = graph.start(kame_command("kame.cli.tf_monitor", "world", "camera"))
    monitor.wait_line("Chain is: world -> base -> camera", timeout=20)
    monitor.wait_line("Frame: base published by /fixed(static) Average Delay: 0 Max Delay: 0")
    broadcaster = monitor.wait_line("Node: /moving ")
    assert " Hz, Average Delay: -0.0" in broadcaster  # stamped a period (0.1 s) ahead


@debian
def test_debians_tf_monitor_hears_kames_broadcasters(graph: Graph) -> None:
    graph.start([*STATIC_TF2, "1", "0", "0", "0", "0", "0", "world", "base", "__name:=fixed"])
    graph.start([*STATIC_TF, "0", "1", "0", "0", "0", "0", "base", "camera", "100", "__name:=moving"])
    monitor = graph.start(["/usr/lib/tf/tf_monitor", "world", "camera"])
    monitor.wait_line("Chain is: world -> base -> camera", timeout=30)
    # Debian's tf_monitor names no publisher, for Debian's own publishers too
    monitor.wait_line("Frame: base published by unknown_publisher(static) Average Delay: 0 Max Delay: 0")
    monitor.wait_line("Frame: camera published by unknown_publisher Average Delay: -0.0")
    assert " Hz, Average Delay: -0.0" in monitor.wait_line("Node: unknown_publisher ")  # a period (0.1 s) ahead


def test_static_publishers_in_a_launch_file(graph: Graph, tmp_path: Path) -> None:
    """The way launch files use them: tf's with its period, tf2_ros's with yaw pitch roll."""
    launch = tmp_path / "frames.launch"
    launch.write_text("""<launch>
  <node pkg="tf" type="static_transform_publisher" name="map_to_odom" args="1 0 0 0 0 0 map odom 100"/>
  <node pkg="tf2_ros" type="static_transform_publisher" name="odom_to_laser"
        args="0 2 0 1.5707963267948966 0 0 odom laser"/>
</launch>
""")
    graph.start(kame_command("kame.cli.roslaunch", str(launch)))
    echo = graph.start([*TF_ECHO, "map", "laser", "5"])
    echo.wait_line("- Translation: [1.000, 2.000, 0.000]", timeout=30)
    echo.wait_line("            in RPY (degree) [0.000, -0.000, 90.000]")


def test_tf_echo_private_parameters(graph: Graph) -> None:
    graph.start([*STATIC_TF2, "1", "2", "3", "0", "0", "0", "map", "odom"])
    echo = graph.start([*TF_ECHO, "map", "odom", "_precision:=1", "_rate:=10"])
    echo.wait_line("- Translation: [1.0, 2.0, 3.0]", timeout=20)
    bad = subprocess.run([*TF_ECHO, "map", "odom", "_precision:=0"], env=graph.env, capture_output=True, text=True,
                         timeout=30)
    assert (bad.returncode, bad.stderr) == (255, "Precision must be > 0\n")


def test_sim_time_stamps_from_clock(graph: Graph) -> None:
    """With /use_sim_time (a bag played with --clock, a simulator), tf's periodic publisher stamps
    with /clock a period ahead and waits a period of /clock between messages, as ros::Duration's
    sleep does: a clock that steps half a second twice a second gets one message a step, never the
    same stamp twice (roscpp's listeners warn TF_REPEATED_DATA and drop such repeats)."""
    subprocess.run([sys.executable, "-m", "kame.cli.rosparam", "set", "/use_sim_time", "true"], env=graph.env,
                   check=True, timeout=30)
    graph.kame("""
        import rospy
        from rosgraph_msgs.msg import Clock
        rospy.init_node('clock', disable_rostime=True)
        pub = rospy.Publisher('/clock', Clock, queue_size=1)
        now = rospy.Time(100)
        while not rospy.is_shutdown():
            pub.publish(Clock(clock=now))
            now += rospy.Duration(0.5)
            rospy.sleep(0.5)
    """)
    graph.start([*STATIC_TF, "1", "0", "0", "0", "0", "0", "map", "odom", "100"])
    echo = graph.start([*kame_command("kame.cli.rostopic"), "echo", "/tf/transforms[0]/header/stamp"])
    deadline = time.monotonic() + 60
    while sum(line.startswith("secs:") for line in list(echo.out)) < 8:
        assert time.monotonic() < deadline, "".join(echo.out)
        time.sleep(0.1)
    shown = "".join(echo.out).split("---\n")[:8]
    assert len(set(shown)) == len(shown), shown
    # a period (0.1 s) ahead of a clock on whole and half seconds
    assert all(stamp.split("nsecs: ")[1].split()[0] in ("100000000", "600000000") for stamp in shown), shown
