"""ROS_IPV6: roscore on the IPv6 loopback (ROS_IPV6=on, ROS_IP=::1, ROS_MASTER_URI=http://[::1]:PORT/),
rospy's talker and listener (kame's) exchanging messages, and the tools reaching the nodes:
every URI names [::1] in brackets, as an IPv6 address must be in a URI."""

from __future__ import annotations

import socket
import subprocess
import xmlrpc.client
from pathlib import Path

import pytest

from ..support import Proc, ros_env, wait_for_master
from ..support.hosts import BIN


def _ipv6_loopback_missing() -> str | None:
    try:
        shown = subprocess.run(["ip", "-6", "addr", "show", "lo"], capture_output=True, text=True, timeout=10)
    except FileNotFoundError:
        return "iproute2's ip is not installed"
    if "inet6 ::1/128" not in shown.stdout:
        return f"lo has no ::1 (IPv6 is off on this machine): {shown.stdout.strip() or shown.stderr.strip()}"
    return None


pytestmark = pytest.mark.skipif(_ipv6_loopback_missing() is not None, reason=_ipv6_loopback_missing() or "")


def free_ipv6_port() -> int:
    with socket.socket(socket.AF_INET6) as s:
        s.bind(("::1", 0))
        return int(s.getsockname()[1])


def test_a_master_on_the_ipv6_loopback_and_a_talker_and_listener_on_it(tmp_path: Path) -> None:
    port = free_ipv6_port()
    uri = f"http://[::1]:{port}/"
    env = ros_env(tmp_path, uri)
    del env["ROS_HOSTNAME"]
    env.update(ROS_IPV6="on", ROS_IP="::1")
    procs = [Proc([str(BIN / "roscore"), "-p", str(port)], env, cwd=tmp_path)]
    try:
        wait_for_master(uri, timeout=30, proc=procs[0])
        master = xmlrpc.client.ServerProxy(uri)
        assert master.getUri("/test")[2] == uri
        listener = Proc([str(BIN / "rosrun"), "rospy_tutorials", "listener.py"], env, cwd=tmp_path)
        procs.append(listener)
        procs.append(Proc([str(BIN / "rosrun"), "rospy_tutorials", "talker.py"], env, cwd=tmp_path))
        listener.wait_line("I heard hello world", timeout=60)
        launch_uris = master.getParam("/test", "/roslaunch/uris")[2]  # roscore's own roslaunch server
        assert [str(u).startswith("http://[::1]:") for u in launch_uris.values()] == [True], launch_uris

        nodes = subprocess.run([str(BIN / "rosnode"), "list"], env=env, capture_output=True, text=True, timeout=60,
                               check=True).stdout.split()
        [talker] = [n for n in nodes if n.startswith("/talker_")]
        [listener_name] = [n for n in nodes if n.startswith("/listener_")]
        for node in (talker, listener_name):
            assert master.lookupNode("/test", node)[2].startswith("http://[::1]:")
        # the talker's service, over rosrpc://[::1]:port
        [_, _, service_uri] = master.lookupService("/test", f"{talker}/get_loggers")
        assert service_uri.startswith("rosrpc://[::1]:")
        loggers = subprocess.run([str(BIN / "rosservice"), "call", f"{talker}/get_loggers"], env=env,
                                 capture_output=True, text=True, timeout=60)
        assert loggers.returncode == 0 and "rosout" in loggers.stdout, loggers.stdout + loggers.stderr
        # rosnode info reaches the talker over IPv6 and lists its connection to the listener
        info = subprocess.run([str(BIN / "rosnode"), "info", talker], env=env, capture_output=True, text=True,
                              timeout=60, check=True).stdout
        assert "contacting node http://[::1]:" in info and listener_name in info, info
    finally:
        for proc in reversed(procs):
            proc.stop()
