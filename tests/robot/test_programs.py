"""The robot programs as a course runs them: a launch file sets robot_description from a xacro
file (`command="$(find xacro)/xacro ..."`, args passed through), joint_state_publisher publishes
the joints (one started at `~zeros`), robot_state_publisher turns them into tf, and tf_echo sees
the moving and the fixed frames where the URDF puts them; a rospy script reads the description
with urdf_parser_py's URDF.from_parameter_server; rviz's RobotModel draws the links where tf
puts them (the window in its own process on a private Xvfb)."""

from __future__ import annotations

import subprocess
import sys
import xmlrpc.client
from pathlib import Path

import pytest

from tests.support import Proc
from tests.turtlesim.sim import BIN, master, wait_until

pytest.importorskip("urdf_parser_py", reason="the robot programs parse URDF with urdf_parser_py (kame[robot])")
pytest.importorskip("xacro", reason="the xacro command needs kame[robot]")

ARM_XACRO = """<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="len" default="1.0"/>
  <xacro:property name="len" value="$(arg len)"/>
  <xacro:macro name="segment" params="n parent">
    <link name="link${n}"><visual><geometry><box size="0.1 0.1 ${len}"/></geometry>
      <material name="red"><color rgba="1 0 0 1"/></material></visual></link>
    <joint name="j${n}" type="revolute"><parent link="${parent}"/><child link="link${n}"/>
      <origin xyz="0 0 ${len}"/><axis xyz="0 1 0"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  </xacro:macro>
  <link name="base"/>
  <xacro:segment n="1" parent="base"/>
  <xacro:segment n="2" parent="link1"/>
  <joint name="mount" type="fixed"><parent link="base"/><child link="base_footprint"/>
    <origin xyz="0 0 -0.5"/></joint>
  <xacro:include filename="$(find turtlebot_description)/urdf/turtlebot.urdf"/>
</robot>
"""

LAUNCH = """<launch>
  <arg name="len" default="0.25"/>
  <param name="robot_description" command="$(find xacro)/xacro $(dirname)/arm.urdf.xacro len:=$(arg len)"/>
  <node name="joint_state_publisher" pkg="joint_state_publisher" type="joint_state_publisher">
    <rosparam param="zeros">{j1: 0.5}</rosparam>
  </node>
  <node name="robot_state_publisher" pkg="robot_state_publisher" type="robot_state_publisher"/>
</launch>
"""

READ_DESCRIPTION = """
import rospy
from urdf_parser_py.urdf import URDF
rospy.init_node("reader", anonymous=True)
robot = URDF.from_parameter_server()
print(robot.name, sorted(j.name for j in robot.joints), robot.link_map["link1"].visual.geometry.size)
"""


def _echo(sim, source: str, target: str) -> tuple[str, str]:  # type: ignore[no-untyped-def]
    """tf_echo's first translation and rotation lines for `target` in `source`."""
    echo = Proc([str(BIN / "rosrun"), "tf", "tf_echo", source, target], sim.env, cwd=sim.home)
    sim.procs.append(echo)
    try:
        return echo.wait_line("- Translation", timeout=30).strip(), echo.wait_line("- Rotation", timeout=5).strip()
    finally:
        echo.stop()


def test_xacro_expands_macros_args_and_find(tmp_path: Path) -> None:
    (tmp_path / "arm.urdf.xacro").write_text(ARM_XACRO)
    done = subprocess.run([str(BIN / "xacro"), str(tmp_path / "arm.urdf.xacro"), "len:=0.25"], capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert '<box size="0.1 0.1 0.25"/>' in done.stdout and '<joint name="j2" type="revolute">' in done.stdout
    assert '<link name="base_scan">' in done.stdout  # the included turtlebot.urdf, found through $(find)
    (tmp_path / "lost.xacro").write_text('<robot name="x" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                                         '<xacro:include filename="$(find no_such_package)/a.urdf"/></robot>')
    for args, reason in (([str(tmp_path / "lost.xacro")], "[no_such_package] not found"),
                         ([str(tmp_path / "missing.xacro")], "No such file or directory")):
        failed = subprocess.run([str(BIN / "xacro"), *args], capture_output=True, text=True, timeout=60)
        assert failed.returncode != 0 and reason in failed.stderr and "Traceback" not in failed.stderr, failed.stderr


def test_the_xacro_distributions_own_command_finds_kames_packages_too(tmp_path: Path) -> None:
    """Its console script and kame's are both `xacro`; an installer that puts the distribution's
    last (uv's parallel install, `pip install -U xacro`) must not bring back ament's $(find)."""
    (tmp_path / "arm.urdf.xacro").write_text(ARM_XACRO)
    their_script = "import sys, xacro; sys.argv[0] = 'xacro'; xacro.main()"
    done = subprocess.run([sys.executable, "-c", their_script, str(tmp_path / "arm.urdf.xacro")], capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert '<link name="base_scan">' in done.stdout  # the included turtlebot.urdf, found through $(find)
    failed = subprocess.run([sys.executable, "-c", their_script, str(tmp_path / "missing.xacro")], capture_output=True,
                            text=True, timeout=60)
    assert failed.returncode != 0 and "No such file or directory" in failed.stderr, failed.stderr
    assert "Traceback" not in failed.stderr, failed.stderr


def test_a_launched_xacro_robot_shows_up_in_tf(tmp_path: Path) -> None:
    (tmp_path / "arm.urdf.xacro").write_text(ARM_XACRO)
    (tmp_path / "arm.launch").write_text(LAUNCH)
    with master(tmp_path / "home") as sim:
        launched = Proc([str(BIN / "roslaunch"), str(tmp_path / "arm.launch")], sim.env, cwd=sim.home)
        sim.procs.append(launched)
        launched.wait_line("process[robot_state_publisher-", timeout=60)
        # j1 starts at 0.5 rad about y, 0.25 m up; j2 at 0 another 0.25 m up link1's turned z
        translation, rotation = _echo(sim, "base", "link1")
        assert translation == "- Translation: [0.000, 0.000, 0.250]"
        assert rotation == "- Rotation: in Quaternion [0.000, 0.247, 0.000, 0.969]"
        translation, _ = _echo(sim, "base", "link2")
        assert translation == "- Translation: [0.120, 0.000, 0.469]"  # 0.25 sin 0.5, 0.25 + 0.25 cos 0.5
        translation, _ = _echo(sim, "base", "base_scan")  # fixed joints, on /tf_static
        assert translation == "- Translation: [0.000, 0.000, -0.203]"  # -0.5 + 0.0102 + 0.287
        read = subprocess.run([sys.executable, "-c", READ_DESCRIPTION], env=sim.env, capture_output=True, text=True,
                              timeout=60)
        assert read.returncode == 0, read.stderr
        assert read.stdout.split("\n")[0] == (
            "arm ['base_joint', 'j1', 'j2', 'mount', 'scan_joint'] [0.1, 0.1, 0.25]")


RVIZ_FILE = """\
Visualization Manager:
  Displays:
    - {Class: rviz/RobotModel, Name: RobotModel, Enabled: true, Robot Description: robot_description}
    - {Class: rviz/TF, Name: TF, Enabled: true}
  Global Options:
    Background Color: 48; 48; 48
    Fixed Frame: base
  Views:
    Current: {Class: rviz/TopDownOrtho, Scale: 200, X: 0, Y: 0}
"""


def test_rviz_draws_the_launched_robot_where_tf_puts_its_links(tmp_path: Path) -> None:
    pytest.importorskip("OpenGL", reason="rviz draws through PyOpenGL (pip install 'kame[gui]')")
    pytest.importorskip("PySide6")
    from tests.support import REPO
    from tests.turtlesim.xserver import xvfb

    (tmp_path / "arm.urdf.xacro").write_text(ARM_XACRO)
    (tmp_path / "arm.launch").write_text(LAUNCH)
    (tmp_path / "arm.rviz").write_text(RVIZ_FILE)
    with master(tmp_path / "home") as sim, xvfb() as display:
        launched = Proc([str(BIN / "roslaunch"), str(tmp_path / "arm.launch")], sim.env, cwd=sim.home)
        sim.procs.append(launched)
        launched.wait_line("process[robot_state_publisher-", timeout=60)
        rviz = Proc([sys.executable, "-m", "tests.rviz.live_child", sim.uri, str(tmp_path / "arm.rviz"), "link1",
                     "link2", "--colour", "255,0,0"], dict(sim.env, DISPLAY=display), cwd=REPO)
        sim.procs.append(rviz)
        wanted = "status RobotModel:Ok;TF:Ok colour "

        def robot_drawn() -> list[str]:  # tf fills in after the first frames
            return [line for line in list(rviz.out)
                    if wanted in line and "link2=none" not in line and int(line.rsplit(" ", 1)[1]) > 0]

        wait_until(lambda: bool(robot_drawn()), timeout=90, what="rviz to draw the robot")
        line = robot_drawn()[-1]
        frames = dict(part.split("=") for part in line.split(" status ")[0].split()[1:])
        assert frames["link2"].startswith("0.120,0.000,"), line  # 0.25 sin 0.5 along x, seen from above
        assert int(line.rsplit(" ", 1)[1]) > 100, line  # the red links drawn


def test_joint_state_publisher_gui_publishes_the_sliders_and_stops_on_ctrl_c(tmp_path: Path) -> None:
    pytest.importorskip("PySide6")
    (tmp_path / "arm.urdf.xacro").write_text(ARM_XACRO)
    with master(tmp_path / "home") as sim:
        expanded = subprocess.run([str(BIN / "xacro"), str(tmp_path / "arm.urdf.xacro")], capture_output=True,
                                  text=True, timeout=60, check=True).stdout
        sim.run("rosparam", "set", "robot_description", expanded)
        gui = Proc([str(BIN / "rosrun"), "joint_state_publisher_gui", "joint_state_publisher_gui"],
                   dict(sim.env, QT_QPA_PLATFORM="offscreen"), cwd=sim.home)
        sim.procs.append(gui)
        echoed = sim.run("rostopic", "echo", "-n", "1", "/joint_states", timeout=60)
        assert "name: \n  - j1\n  - j2\nposition: [0.0, 0.0]\n" in echoed.stdout
        gui.stop(timeout=20)
        assert gui.popen.returncode == 0, "".join(gui.err)  # Ctrl-C closed its window: not killed by it
        # its node shut down and left the master: no dead publisher of /joint_states in the graph
        publishers = dict(xmlrpc.client.ServerProxy(sim.uri).getSystemState("/test")[2][0])
        assert not publishers.get("/joint_states"), publishers


def test_robot_state_publisher_without_a_description_says_so_and_the_old_name_warns(tmp_path: Path) -> None:
    with master(tmp_path / "home") as sim:
        done = sim.run("rosrun", "robot_state_publisher", "state_publisher", check=False, timeout=60)
        assert done.returncode == 1
        assert "The 'state_publisher' executable is deprecated" in done.stderr
        assert "Could not find parameter robot_description on parameter server" in done.stderr
        sim.run("rosparam", "set", "robot_description", "<robot><link name='a'>")
        done = sim.run("rosrun", "robot_state_publisher", "robot_state_publisher", check=False, timeout=60)
        assert done.returncode == 1 and "Failed to extract kdl tree from xml robot description" in done.stderr
        looped = ("<robot name='loop'><link name='a'/><link name='b'/>"
                  "<joint name='ab' type='fixed'><parent link='a'/><child link='b'/></joint>"
                  "<joint name='ba' type='fixed'><parent link='b'/><child link='a'/></joint></robot>")
        sim.run("rosparam", "set", "robot_description", looped)
        done = sim.run("rosrun", "robot_state_publisher", "robot_state_publisher", check=False, timeout=60)
        assert done.returncode == 1
        (line,) = done.stderr.strip().splitlines()  # roscpp's console line, nothing more
        assert line.endswith("]: Failed to extract kdl tree from xml robot description: No roots detected, invalid "
                             "URDF: every link has a parent joint, and joints [ab] -> [ba] form a loop\x1b[0m"), line
