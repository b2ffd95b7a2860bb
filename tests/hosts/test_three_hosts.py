"""ROS across machines: three hosts (network namespaces on a private bridge, tests/support/netns.py)
named robot, laptop and tablet in each other's hosts files, every program told its own name by
ROS_HOSTNAME, as a lab sets them up. The master runs on robot; the programs on laptop and tablet
talk through it and to each other, kame with kame and with Debian's rospy and roscpp.

Needs root (skips without it). One set of hosts and one master serve the whole module; every
process is stopped by its PID and every namespace is deleted at the end.
"""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml

from ..support import SYSTEM_PYTHON, Proc, have_debian_ros
from ..support.hosts import BIN, Hosts
from ..support.netns import Lan
from ..support.roscpp import build_peers, roscpp_flags

pytestmark = pytest.mark.skipif(Lan.unavailable() is not None, reason=Lan.unavailable() or "")

TUTORIALS = Path(__file__).parents[1] / "interop" / "tutorials"
debian = pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 (rospy, ros* tools) is not installed")


def pose_x(hosts: Hosts, host: str, **env: str) -> float:
    out = hosts.run(host, [str(BIN / "rostopic"), "echo", "-n", "1", "/turtle1/pose"], **env)
    return float(yaml.safe_load(out.split("---")[0])["x"])


def drive_until_moved(hosts: Hosts, teleop: Proc, host: str, timeout: float = 20.0, **env: str) -> None:
    """Up-arrow presses into teleop (on its stdin) until `rostopic echo` on `host` sees the turtle go 1 m forward."""
    assert teleop.popen.stdin is not None
    start = pose_x(hosts, host, **env)
    deadline = time.monotonic() + timeout
    while pose_x(hosts, host, **env) < start + 1.0:
        assert time.monotonic() < deadline, "the turtle never moved"
        teleop.popen.stdin.write("\x1b[A")
        teleop.popen.stdin.flush()


def test_turtlesim_on_laptop_driven_by_teleop_and_watched_from_tablet(cleanup: Hosts) -> None:
    hosts = cleanup
    sim = hosts.start("laptop", [str(BIN / "rosrun"), "turtlesim", "turtlesim_node", "--headless"])
    sim.wait_line("runs without a window")
    teleop = hosts.start("tablet", [str(BIN / "rosrun"), "turtlesim", "turtle_teleop_key"], stdin=subprocess.PIPE)
    teleop.wait_line("Use arrow keys to move the turtle.")
    drive_until_moved(hosts, teleop, "tablet")
    # a service across hosts: robot asks laptop's turtlesim for a second turtle
    spawned = hosts.run("robot", [str(BIN / "rosservice"), "call", "/spawn", "1.0", "1.0", "0.0", "t2"])
    assert yaml.safe_load(spawned) == {"name": "t2"}
    nodes = hosts.run("robot", [str(BIN / "rosnode"), "list"]).split()
    assert "/turtlesim" in nodes
    uri = hosts.run("robot", [str(BIN / "rosnode"), "info", "/turtlesim"])
    assert "contacting node http://laptop:" in uri


@debian
def test_kame_talker_heard_by_rospy_and_roscpp_on_another_host_and_back(cleanup: Hosts) -> None:
    hosts = cleanup
    flags = roscpp_flags()
    hosts.start("laptop", [sys.executable, str(TUTORIALS / "talker.py")])
    rospy_listener = hosts.start("tablet", [SYSTEM_PYTHON, str(TUTORIALS / "listener.py")])
    assert "I heard hello world" in rospy_listener.wait_line("I heard hello world", timeout=20)
    if flags is not None:
        cpp_listener = hosts.start("tablet", [str(build_peers(flags)["listener"])])
        cpp_listener.wait_line("I heard: [hello world ", timeout=20)
    # the reverse: Debian's rospy talker on tablet, kame's listener on laptop
    hosts.start("tablet", [SYSTEM_PYTHON, str(TUTORIALS / "talker.py"), "chatter:=from_tablet"])
    kame_listener = hosts.start("laptop", [sys.executable, str(TUTORIALS / "listener.py"), "chatter:=from_tablet"])
    kame_listener.wait_line("I heard hello world", timeout=20)
    if flags is not None:  # and roscpp's talker on tablet, heard by kame on laptop
        hosts.start("tablet", [str(build_peers(flags)["talker"]), "chatter:=from_cpp"])
        kame_listener = hosts.start("laptop", [sys.executable, str(TUTORIALS / "listener.py"), "chatter:=from_cpp"])
        kame_listener.wait_line("I heard hello ", timeout=20)  # roscpp's talker says "hello <n>"


def test_action_server_on_laptop_client_on_tablet(cleanup: Hosts) -> None:
    hosts = cleanup
    hosts.start("laptop", [str(BIN / "rosrun"), "actionlib_tutorials", "fibonacci_server.py"])
    out = hosts.run("tablet", [str(BIN / "rosrun"), "actionlib_tutorials", "fibonacci_client.py"], timeout=30)
    assert "Result: 0, 1, 1, 2, 3, 5, 8" in out


def test_rosbag_on_robot_records_topics_published_on_laptop_and_tablet(cleanup: Hosts) -> None:
    hosts = cleanup
    bag = hosts.home / "two_hosts.bag"
    hosts.start("laptop", [str(BIN / "rostopic"), "pub", "-r", "20", "/from_laptop", "std_msgs/String", "laptop"])
    hosts.start("tablet", [str(BIN / "rostopic"), "pub", "-r", "20", "/from_tablet", "std_msgs/Int32", "7"])
    record = hosts.start("robot", [str(BIN / "rosbag"), "record", "-O", str(bag), "/from_laptop", "/from_tablet"])
    # rostopic echo on robot proves both publishers are reachable from there before recording is judged
    for topic in ("/from_laptop", "/from_tablet"):
        hosts.run("robot", [str(BIN / "rostopic"), "echo", "-n", "3", topic])
    hosts.run("robot", [str(BIN / "rostopic"), "echo", "-n", "5", "/from_tablet"])
    hosts.stop(record)
    info = hosts.run("robot", [str(BIN / "rosbag"), "info", "-y", "-k", "topics", str(bag)])
    counts = {t["topic"]: t["messages"] for t in yaml.safe_load(info)}
    assert counts.get("/from_laptop", 0) > 0 and counts.get("/from_tablet", 0) > 0, info


def wait_stderr(proc: Proc, text: str, timeout: float = 20.0) -> list[str]:
    """Every stderr line of `proc` containing `text`, once there is one."""
    deadline = time.monotonic() + timeout
    while not (found := [line for line in proc.err if text in line]):
        assert time.monotonic() < deadline and proc.popen.poll() is None, f"no {text!r} in {''.join(proc.err)}"
        time.sleep(0.05)
    return found


def test_a_misnamed_publisher_is_one_warning_at_the_subscriber_and_a_roswtf_error(cleanup: Hosts) -> None:
    hosts = cleanup
    hosts.start("laptop", [str(BIN / "rostopic"), "pub", "-r", "10", "/misnamed", "std_msgs/String", "lost",
                           "__name:=misnamed_talker"], ROS_HOSTNAME="laptop-misnamed")
    listener = hosts.start("tablet", [sys.executable, str(TUTORIALS / "listener.py"), "chatter:=/misnamed"])
    # the topic is there, as in the classic failure, but nothing flows: the one line says why
    deadline = time.monotonic() + 20
    while "/misnamed" not in hosts.run("tablet", [str(BIN / "rostopic"), "list"]).split():
        assert time.monotonic() < deadline, "the misnamed publisher never registered"
    [warning] = wait_stderr(listener, "cannot reach publisher /misnamed_talker of /misnamed at http://laptop-misnamed:")
    assert "its name does not resolve on this machine" in warning and "ROS_HOSTNAME" in warning
    wtf = hosts.run("tablet", [str(BIN / "roswtf")], timeout=60)
    assert "/misnamed_talker advertises [laptop-misnamed:" in wtf, wtf
    _, err = hosts.stop(listener)
    assert err.count("cannot reach publisher") == 1, err
    assert "I heard" not in "".join(listener.out)


PROBE = """
import socket, sys, xmlrpc.client
master, node_uri, tcpros_port = sys.argv[1], sys.argv[2], int(sys.argv[3])

def closed(host, port, data):
    # whether the server closed our connection without a word
    with socket.create_connection((host, port), timeout=5) as sock:
        try:
            sock.sendall(data)
            return sock.recv(100) == b""
        except ConnectionResetError:
            return True

call = xmlrpc.client.dumps(("/outsider",), "getPid").encode()
post = b"POST / HTTP/1.1\\r\\nContent-Length: %d\\r\\n\\r\\n%s" % (len(call), call)
node_host, node_port = node_uri.split("//")[1].rstrip("/").split(":")
print("master", closed("robot", int(master), post))
print("xmlrpc", closed(node_host, int(node_port), post))
print("tcpros", closed(node_host, tcpros_port, b"\\x04\\x00\\x00\\x00abcd"))
"""


def test_an_allowlist_refuses_an_outside_host_at_every_port_and_serves_the_listed(cleanup: Hosts) -> None:
    hosts = cleanup
    guarded = {"ROS_MASTER_URI": "http://robot:11312/", "KAME_ALLOWED_PEERS": "robot laptop"}
    master = hosts.start("robot", [str(BIN / "rosmaster"), "--core", "-p", "11312", "--allowed-peers",
                                   "laptop"], ROS_MASTER_URI="http://robot:11312/")
    hosts.run("laptop", [str(BIN / "rosparam"), "set", "/guarded_up", "1"], retry=True, **guarded)
    talker = [str(BIN / "rostopic"), "pub", "-r", "10", "/guarded", "std_msgs/String", "inside", "__name:=guarded"]
    guarded_talker = hosts.start("laptop", talker, **guarded)
    # laptop is on the list: kame and Debian's rospy there work as ever
    listener = hosts.start("laptop", [SYSTEM_PYTHON if have_debian_ros() else sys.executable,
                                      str(TUTORIALS / "listener.py"), "chatter:=/guarded"], **guarded)
    listener.wait_line("I heard inside", timeout=20)
    # what tablet would be told, asked from robot (this machine, so always allowed)
    node_uri = hosts.run("robot", [sys.executable, "-c", (
        "import sys, xmlrpc.client as x; m = x.ServerProxy('http://robot:11312/'); uri = m.lookupNode('/p', "
        "'/guarded')[2]; print(uri, x.ServerProxy(uri).requestTopic('/p', '/guarded', [['TCPROS']])[2][2])")],
        retry=True).split()
    refused = hosts.run("tablet", [sys.executable, "-c", PROBE, "11312", node_uri[0], node_uri[1]])
    assert refused.split() == ["master", "True", "xmlrpc", "True", "tcpros", "True"], refused
    hosts.stop(master)
    master_log = (hosts.home / "robot" / "log" / "master.log").read_text()
    assert master_log.count("refused a connection to the master from 10.231.0.3: it is not in "
                            "KAME_ALLOWED_PEERS [laptop]") == 1, master_log
    _, talker_err = hosts.stop(guarded_talker)
    for server in ("kame-xmlrpc", "kame-tcpros"):
        assert talker_err.count(f"refused a connection to the {server} from 10.231.0.3: it is not in "
                                "KAME_ALLOWED_PEERS [robot laptop]") == 1, talker_err


def test_roswtf_says_when_the_master_on_another_host_cannot_be_reached(hosts: Hosts) -> None:
    out = hosts.run("tablet", [str(BIN / "roswtf")], timeout=60, ROS_MASTER_URI="http://robot:11399/")
    assert "ROS Master does not appear to be running." in out
    assert "The master's machine cannot be reached from here: the connection was refused." in out, out


def test_roscore_restarted_under_turtlesim_and_teleop_on_other_hosts_and_the_turtle_moves_again(
        cleanup: Hosts) -> None:
    hosts = cleanup
    own = {"ROS_MASTER_URI": "http://robot:11313/"}  # a master of its own, to restart
    core = [str(BIN / "roscore"), "-p", "11313"]
    master = hosts.start("robot", core, **own)
    hosts.run("robot", [str(BIN / "rosparam"), "set", "/restart_up", "1"], retry=True, **own)
    sim = hosts.start("laptop", [str(BIN / "rosrun"), "turtlesim", "turtlesim_node", "--headless"], **own)
    sim.wait_line("runs without a window")
    teleop = hosts.start("tablet", [str(BIN / "rosrun"), "turtlesim", "turtle_teleop_key"], stdin=subprocess.PIPE,
                         **own)
    teleop.wait_line("Use arrow keys to move the turtle.")
    drive_until_moved(hosts, teleop, "tablet", **own)
    hosts.stop(master)
    master = hosts.start("robot", core, **own)
    hosts.run("robot", [str(BIN / "rosparam"), "get", "/rosdistro"], retry=True, **own)
    restarted = time.monotonic()
    deadline = restarted + 20
    while not {"/turtlesim", "/teleop_turtle"} <= set(hosts.run("robot", [str(BIN / "rosnode"), "list"],
                                                                **own).split()):
        assert time.monotonic() < deadline, "turtlesim and teleop never registered with the new master"
    print(f"turtlesim and teleop listed again {time.monotonic() - restarted:.2f} s after the new master answered")
    # the same teleop, never restarted, drives the same turtle again
    drive_until_moved(hosts, teleop, "tablet", **own)


def test_roswtf_on_a_host_that_advertises_loopback_with_the_master_elsewhere_is_an_error(hosts: Hosts) -> None:
    out = hosts.run("tablet", [str(BIN / "roswtf")], timeout=60, ROS_HOSTNAME="localhost")
    [line] = [line for line in out.splitlines() if "Nodes on other machines cannot reach this one: " in line]
    assert "[localhost], which means [127.0.0.1]" in line and "ROS_IP" in line, out
