"""roslaunch's Python API as scripts use it: scriptapi.ROSLaunch and parent.ROSLaunchParent."""

from __future__ import annotations

import os
import re
import sys
import xmlrpc.client
from pathlib import Path

from tests.support import Proc, free_port, ros_env

SCRIPT = """
import os, sys, time, xmlrpc.client
import roslaunch, roslaunch.pmon, roslaunch.rlutil
from roslaunch.core import Node

launch = roslaunch.scriptapi.ROSLaunch()
launch.start()
talker = launch.launch(Node("rospy_tutorials", "talker", name="talker", namespace="ns",
                            remap_args=[("chatter", "chat9")]))
master = xmlrpc.client.ServerProxy(os.environ["ROS_MASTER_URI"])
deadline = time.monotonic() + 15
while time.monotonic() < deadline:
    if ["/ns/chat9", ["/ns/talker"]] in master.getSystemState("/t")[2][0]:
        break
    time.sleep(0.05)
print("alive", talker.is_alive(), "pid", talker.pid, flush=True)
talker.stop()
print("after stop", talker.is_alive(), flush=True)
launch.stop()

class Listener(roslaunch.pmon.ProcessListener):
    def process_died(self, name, exit_code):
        print("died", name, exit_code, flush=True)


class Broken(roslaunch.pmon.ProcessListener):
    def process_died(self, name, exit_code):
        raise RuntimeError("a listener's own bug")


run_id = roslaunch.rlutil.get_or_generate_uuid(None, False)
roslaunch.configure_logging(run_id)
files = roslaunch.rlutil.resolve_launch_arguments([sys.argv[1], "rate:=5"])
parent = roslaunch.parent.ROSLaunchParent(run_id, [(files[0], ["rate:=5"])], show_summary=False,
                                          process_listeners=[Broken(), Listener()])
parent.start()
print("rate", master.getParam("/t", "/rate")[2], flush=True)
parent.spin()
print("spun", flush=True)
"""


def test_scriptapi_and_parent(tmp_path: Path) -> None:
    port = free_port()
    env = ros_env(tmp_path / "home", f"http://127.0.0.1:{port}")
    launch_file = tmp_path / "short.launch"
    launch_file.write_text('<launch><arg name="rate" default="1"/><param name="rate" value="$(arg rate)"/>'
                           '<node name="brief" pkg="rospy_tutorials" type="talker" launch-prefix="timeout 1"/>'
                           "</launch>")
    script = tmp_path / "script.py"
    script.write_text(SCRIPT)
    core = Proc([sys.executable, "-m", "kame.cli.roscore", "-p", str(port)], env)
    try:
        core.wait_line("started core service", timeout=20)
        proc = Proc([sys.executable, str(script), str(launch_file)], env)
        proc.popen.wait(40)
        out, err = proc.stop()
        assert proc.popen.returncode == 0, out + err
        assert "alive True pid" in out and "after stop False" in out
        assert "rate 5" in out and "spun" in out
        assert re.search(r"died brief-\d+ 124", out), out  # `timeout 1` ends it with 124; the broken one is said
        assert "process listener" in err and "a listener's own bug" in err
        logged = re.search(r"\.\.\. logging to (\S+/roslaunch-\S+\.log)", out)
        assert logged and Path(logged.group(1)).is_file(), out
        pid = int(re.search(r"alive True pid (\d+)", out)[1])  # type: ignore[index]
        assert not os.path.exists(f"/proc/{pid}")
        assert xmlrpc.client.ServerProxy(f"http://127.0.0.1:{port}").getParam("/t", "/rate")[2] == 5
    finally:
        core.stop()
