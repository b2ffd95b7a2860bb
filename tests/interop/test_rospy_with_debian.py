"""The rospy tutorials on kame, and kame nodes talking with Debian's real ROS 1 both ways.

The tutorial programs in tutorials/ are the ROS wiki's, unchanged but for print(); each runs
under kame's interpreter and, where the test says so, under Debian's rospy (/usr/bin/python3).
Every process is stopped by its PID.
"""

from __future__ import annotations

import os
import signal
import sys
import time
import xmlrpc.client
from collections.abc import Iterator
from pathlib import Path

import pytest

from ..support import (
    SYSTEM_PYTHON,
    Proc,
    free_port,
    have_debian_ros,
    kame_command,
    ros_env,
    ros_tool,
    wait_for_master,
)

TUTORIALS = Path(__file__).with_name("tutorials")
PEER = Path(__file__).with_name("ros_peer_node.py")
debian = pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 (rospy, ros* tools) is not installed")


class Graph:
    def __init__(self, home: Path) -> None:
        self.home = home
        self.port = free_port()
        self.uri = f"http://127.0.0.1:{self.port}/"
        self.env = ros_env(home, self.uri)
        self.master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(self.port)), self.env)
        self.procs: list[Proc] = []
        wait_for_master(self.uri, proc=self.master)

    def kame(self, script: str, *args: str) -> Proc:
        proc = Proc([sys.executable, str(TUTORIALS / script), *args], self.env)
        self.procs.append(proc)
        return proc

    def kame_code(self, code: str) -> Proc:
        proc = Proc([sys.executable, "-c", code], self.env)
        self.procs.append(proc)
        return proc

    def real(self, script: Path | str, *args: str) -> Proc:
        proc = Proc([SYSTEM_PYTHON, str(script), *args], self.env)
        self.procs.append(proc)
        return proc

    def real_code(self, code: str) -> Proc:
        proc = Proc([SYSTEM_PYTHON, "-c", code], self.env)
        self.procs.append(proc)
        return proc

    def tool(self, name: str, *args: str, check: bool = True) -> str:
        return ros_tool(name, *args, env=self.env, check=check, timeout=20).stdout

    def state(self) -> list[list[list[str]]]:
        result: list[list[list[str]]] = xmlrpc.client.ServerProxy(self.uri).getSystemState("/test")[2]
        return result

    def nodes(self) -> set[str]:
        return {n for group in self.state() for _, members in group for n in members}

    def stop(self) -> None:
        for proc in reversed(self.procs):
            proc.stop()
        self.master.stop()


@pytest.fixture
def graph(tmp_path: Path) -> Iterator[Graph]:
    g = Graph(tmp_path)
    try:
        yield g
    finally:
        g.stop()


def wait_until(condition: object, timeout: float = 15.0) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition():  # type: ignore[operator]
            return True
        time.sleep(0.05)
    return False


def test_tutorial_talker_and_listener_on_kame(graph: Graph) -> None:
    talker = graph.kame("talker.py")
    listener = graph.kame("listener.py")
    line = listener.wait_line("I heard hello world")
    assert line.startswith("[INFO] [") and "]: /listener_" in line
    assert talker.wait_line("[INFO] [").endswith("\n")
    for proc in (talker, listener):
        started = time.monotonic()
        os.kill(proc.pid, signal.SIGINT)
        assert proc.popen.wait(5) == 0
        assert time.monotonic() - started < 1.0
        assert "Traceback" not in "".join(proc.err)
    assert wait_until(lambda: not any(n.startswith(("/talker", "/listener")) for n in graph.nodes()), 3)


def test_tutorial_services_on_kame(graph: Graph) -> None:
    server = graph.kame("add_two_ints_server.py")
    server.wait_line("Ready to add two ints.")
    client = graph.kame("add_two_ints_client.py", "1", "2")
    assert client.popen.wait(15) == 0
    out, err = client.stop()
    assert out.splitlines() == ["Requesting 1+2", "1 + 2 = 3"], err
    assert server.wait_line("Returning [1 + 2 = 3]")


def test_a_node_waits_for_the_master_and_ctrl_c_ends_it(tmp_path: Path) -> None:
    env = ros_env(tmp_path, f"http://127.0.0.1:{free_port()}/")
    proc = Proc([sys.executable, str(TUTORIALS / "talker.py")], env)
    try:
        deadline = time.monotonic() + 15
        while "master may not be running yet" not in "".join(proc.err) and time.monotonic() < deadline:
            time.sleep(0.05)
        err = "".join(proc.err)
        # rospy's words (rospy/impl/registration.py)
        assert f"Unable to immediately register with master node [{env['ROS_MASTER_URI']}]: " \
               "master may not be running yet. Will keep trying." in err
        assert err.count("register with master") == 1
        started = time.monotonic()
        os.kill(proc.pid, signal.SIGINT)
        proc.popen.wait(5)
        assert time.monotonic() - started < 1.0
    finally:
        proc.stop()


@debian
def test_kame_talker_to_real_listener_and_real_talker_to_kame_listener(graph: Graph) -> None:
    graph.kame("talker.py")
    real_listener = graph.real(TUTORIALS / "listener.py")
    assert "I heard hello world" in real_listener.wait_line("I heard")
    real_talker = graph.real(TUTORIALS / "talker.py", "chatter:=chatter2")
    kame_listener = graph.kame("listener.py", "chatter:=chatter2")
    assert "I heard hello world" in kame_listener.wait_line("I heard")
    real_talker.stop()
    kame_listener.stop()


@debian
def test_real_rostopic_echo_and_rosnode_info_on_a_kame_node(graph: Graph) -> None:
    graph.kame("talker.py", "__name:=talker")
    graph.kame("listener.py", "__name:=listener")
    echoed = graph.tool("rostopic", "echo", "-n", "1", "/chatter")
    assert echoed.startswith('data: "hello world ')
    assert wait_until(lambda: "/listener" in graph.tool("rosnode", "info", "/talker"), 10)
    info = graph.tool("rosnode", "info", "/talker")
    assert " * /chatter [std_msgs/String]" in info
    assert " * topic: /chatter\n    * to: /listener\n    * direction: outbound" in info
    assert "    * transport: TCPROS" in info
    assert "Pid: " in info


@debian
def test_latched_topic_reaches_a_late_real_subscriber(graph: Graph) -> None:
    graph.kame_code(
        "import rospy\nfrom std_msgs.msg import String\nrospy.init_node('latcher')\n"
        "p = rospy.Publisher('/latched', String, queue_size=1, latch=True)\np.publish('kept')\n"
        "print('published', flush=True)\nrospy.spin()\n").wait_line("published")
    assert graph.tool("rostopic", "echo", "-n", "1", "/latched") == 'data: "kept"\n---\n'


@debian
def test_services_both_ways_with_real_rospy(graph: Graph) -> None:
    graph.kame_code(
        "import rospy\nfrom std_srvs.srv import SetBool, SetBoolResponse\nrospy.init_node('kame_flag')\n"
        "rospy.Service('kame_flag', SetBool, lambda r: SetBoolResponse(r.data, 'kame says %s' % r.data))\n"
        "print('ready', flush=True)\nrospy.spin()\n").wait_line("ready")
    assert graph.tool("rosservice", "call", "/kame_flag", "true") == 'success: True\nmessage: "kame says True"\n'
    real_client = graph.real_code(
        "import rospy\nfrom std_srvs.srv import SetBool\nrospy.wait_for_service('/kame_flag')\n"
        "p = rospy.ServiceProxy('/kame_flag', SetBool)\nprint(p(False).message, flush=True)\n")
    assert real_client.popen.wait(20) == 0
    assert real_client.stop()[0].strip() == "kame says False"
    graph.real(PEER).wait_line("ready")
    kame_client = graph.kame_code(
        "import rospy\nfrom std_srvs.srv import SetBool\nrospy.init_node('asker')\n"
        "rospy.wait_for_service('/set_flag')\np = rospy.ServiceProxy('/set_flag', SetBool)\n"
        "print(p(True).message, p.call(data=False).success, flush=True)\n")
    assert kame_client.popen.wait(20) == 0
    assert kame_client.stop()[0].strip() == "flag True False"


@debian
def test_md5_mismatch_is_logged_on_both_sides_and_nobody_crashes(graph: Graph) -> None:
    kame_pub = graph.kame_code(
        "import rospy\nfrom std_msgs.msg import String\nrospy.init_node('kame_pub')\n"
        "p = rospy.Publisher('/mixed', String, queue_size=1)\nprint('ready', flush=True)\n"
        "r = rospy.Rate(20)\nwhile not rospy.is_shutdown():\n    p.publish('x')\n    r.sleep()\n")
    kame_pub.wait_line("ready")
    real_sub = graph.real_code(
        "import rospy\nfrom std_msgs.msg import Int32\nrospy.init_node('real_sub')\n"
        "rospy.Subscriber('/mixed', Int32, lambda m: print('got', m, flush=True))\n"
        "print('ready', flush=True)\nrospy.spin()\n")
    real_sub.wait_line("ready")
    # kame says it on the console, as rospy does for its own errors; real rospy subscribers
    # write theirs to the node's log file.
    assert wait_until(lambda: "topic types do not match" in "".join(kame_pub.err), 10)
    assert wait_until(lambda: "topic types do not match" in logged(graph, "real_sub"), 10)
    real_pub = graph.real_code(
        "import rospy\nfrom std_msgs.msg import String\nrospy.init_node('real_pub')\n"
        "p = rospy.Publisher('/mixed2', String, queue_size=1)\nprint('ready', flush=True)\n"
        "r = rospy.Rate(20)\nwhile not rospy.is_shutdown():\n    p.publish('x')\n    r.sleep()\n")
    real_pub.wait_line("ready")
    kame_sub = graph.kame_code(
        "import rospy\nfrom std_msgs.msg import Int32\nrospy.init_node('kame_sub')\n"
        "rospy.Subscriber('/mixed2', Int32, lambda m: print('got', m, flush=True))\n"
        "print('ready', flush=True)\nrospy.spin()\n")
    kame_sub.wait_line("ready")
    assert wait_until(lambda: "topic types do not match" in "".join(kame_sub.err), 10)
    for proc in (kame_pub, real_sub, real_pub, kame_sub):
        assert proc.popen.poll() is None
        assert "got" not in "".join(proc.out)
    assert "Traceback" not in "".join(kame_pub.err + kame_sub.err)


def logged(graph: Graph, node: str) -> str:
    path = graph.home / "log" / f"{node}.log"
    return path.read_text() if path.exists() else ""


@debian
def test_a_parameterised_node_from_the_courses(graph: Graph) -> None:
    driver = graph.kame("circle_driver.py", "_speed:=2.0", "_radius:=0.5")
    driver.wait_line("driving at 2.0 m/s on a 0.5 m circle")
    assert graph.tool("rosparam", "get", "/circle_driver/speed") == "2.0\n"
    echoed = graph.tool("rostopic", "echo", "-n", "1", "/turtle1/cmd_vel")
    assert "linear: \n  x: 2.0" in echoed and "angular: \n  x: 0.0\n  y: 0.0\n  z: 4.0" in echoed
    assert wait_until(lambda: "/circle_driver" in graph.nodes())


def test_kame_talker_to_roscpp_listener_and_roscpp_talker_to_kame_listener(
        graph: Graph, cpp_peers: dict[str, Path]) -> None:
    graph.kame("talker.py")
    cpp_listener = Proc([str(cpp_peers["listener"])], graph.env)
    graph.procs.append(cpp_listener)
    assert cpp_listener.wait_line("I heard: [hello world ").startswith("I heard: [hello world ")
    cpp_talker = Proc([str(cpp_peers["talker"]), "chatter:=from_cpp"], graph.env)
    graph.procs.append(cpp_talker)
    kame_listener = graph.kame("listener.py", "chatter:=from_cpp")
    heard = kame_listener.wait_line("I heard hello ")
    assert "]: /listener_" in heard and heard.rstrip().split("I heard hello ")[1].isdigit()


SHM_PROBE = """
import threading
import rospy
from std_msgs.msg import String
rospy.init_node("shm_probe")
for topic in ("/from_rospy", "/from_cpp"):
    heard = threading.Event()
    sub = rospy.Subscriber(topic, String, lambda msg: heard.set())
    assert heard.wait(30), topic
    print(topic, [link.header.get("kame_shm") for link in sub.impl.links.values() if link.connected], flush=True)
"""


@debian
def test_real_ros_peers_ignore_the_shared_memory_offer_and_keep_tcpros(
        graph: Graph, cpp_peers: dict[str, Path]) -> None:
    graph.env["KAME_SHM"] = "always"  # for the kame processes started from here on
    graph.real(TUTORIALS / "talker.py", "chatter:=from_rospy")
    cpp_talker = Proc([str(cpp_peers["talker"]), "chatter:=from_cpp"], graph.env)
    graph.procs.append(cpp_talker)
    probe = graph.kame_code(SHM_PROBE)  # offers shared memory to both: neither answers it
    assert probe.wait_line("/from_rospy", 40).strip() == "/from_rospy [None]"
    assert probe.wait_line("/from_cpp", 40).strip() == "/from_cpp [None]"
    graph.kame("talker.py")  # Debian's subscribers never offer: the kame publisher keeps TCPROS
    real_listener = graph.real(TUTORIALS / "listener.py")
    assert "I heard hello world" in real_listener.wait_line("I heard")
    cpp_listener = Proc([str(cpp_peers["listener"])], graph.env)
    graph.procs.append(cpp_listener)
    assert cpp_listener.wait_line("I heard: [hello world ").startswith("I heard: [hello world ")
