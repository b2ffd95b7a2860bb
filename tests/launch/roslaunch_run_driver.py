"""A real launch through roslaunch's modules, under Debian's interpreter or kame's, printed as JSON:
ROSLaunchRunner starts the master (none answers at ROS_MASTER_URI), rosout, the parameters and
the nodes of LAUNCH_FILE under a ProcessMonitor; a child (ROSLaunchChildNode) registers with a
parent's server (ROSLaunchParentNode) and launches a node the parent sends it as XML; then
everything is stopped. tests/launch/test_roslaunch_modules.py compares the two.

`python roslaunch_run_driver.py LAUNCH_FILE`
"""

from __future__ import annotations

import io
import json
import sys
import threading
import traceback
from contextlib import redirect_stderr, redirect_stdout
from typing import Any
from xmlrpc.client import ServerProxy

import roslaunch.config
import roslaunch.core
import roslaunch.launch
import roslaunch.pmon
import roslaunch.server

TIMEOUT = 30.0


class Deaths(roslaunch.pmon.ProcessListener):
    """The deaths heard, and an event per process name (its counter left out)."""

    def __init__(self) -> None:
        self.heard: list[list[Any]] = []
        self.events: dict[str, threading.Event] = {}

    def event(self, name: str) -> threading.Event:
        return self.events.setdefault(name, threading.Event())

    def process_died(self, process_name: str, exit_code: int) -> None:
        name = process_name.rsplit("-", 1)[0]
        self.heard.append([name, exit_code])
        self.event(name).set()


def launch(launch_file: str) -> dict[str, Any]:
    config = roslaunch.config.load_config_default([(launch_file, ["who:=me", "code:=4"])], None)
    deaths = Deaths()
    runner = roslaunch.launch.ROSLaunchRunner("run-1", config, sigint_timeout=2.0, sigterm_timeout=1.0)
    runner.add_process_listener(deaths)
    result: dict[str, Any] = {}
    try:
        succeeded, failed = runner.launch()
        result["launched"] = [sorted(s.rsplit("-", 1)[0] for s in succeeded), sorted(failed)]
        master = config.master.get()
        result["params"] = [master.getParam("/t", key)[2] for key in ("/rate", "/who", "/limits", "/run_id")]
        result["first died"] = deaths.event("first").wait(TIMEOUT)
        result["third respawned"] = deaths.event("g/third").wait(TIMEOUT)
        test = config.tests[0]
        runner.run_test(test)
        result["test"] = [test.name, runner.is_node_running(test)]
        result["child"] = child_launch(config)
        result["active"] = sorted(n.rsplit("-", 1)[0] for n in runner.pm.get_active_names())
    finally:
        runner.stop()
    result["deaths"] = sorted({tuple(d) for d in deaths.heard if d[0] in ("first", "g/second", "t")})
    result["master after stop"] = outcome_of_master(config.master.uri)
    return result


def child_launch(config: Any) -> dict[str, Any]:
    """A parent's server, a child registering with it, and the child launching the XML it is sent."""
    parent_pm = roslaunch.pmon.start_process_monitor()
    child_pm = roslaunch.pmon.start_process_monitor()
    parent = roslaunch.server.ROSLaunchParentNode(config, parent_pm)
    deaths = Deaths()
    parent.add_process_listener(deaths)
    logged: list[str] = []
    parent.handler.log = lambda client, level, message: logged.append(f"{client}:{level}:{message}") or (1, "", 1)
    parent.add_child("child-0", roslaunch.server.ChildROSLaunchProcess("child-0", [], {}))
    parent.start()
    child = roslaunch.server.ROSLaunchChildNode("run-1", "child-0", parent.uri, child_pm)
    try:
        child.start()
        children = parent.handler.list_children()
        xml = ('<launch><node pkg="rl_pkg" type="exiter" name="remote_one" args="5"/>'
               '<node pkg="rl_pkg" type="nothing_here" name="remote_two"/></launch>')
        code, msg, (succeeded, failed) = ServerProxy(child.uri).launch(xml)
        died = deaths.event("remote_one").wait(TIMEOUT)
        bad = ServerProxy(child.uri).launch("<launch><node/></launch>")
        return {"registered": children[2] == [child.uri], "launch": [code, msg, [s.rsplit("-", 1)[0]
                                                                                 for s in succeeded], failed],
                "died": [died, deaths.heard], "bad xml": [bad[0], bad[2]],
                "logged": [line for line in logged if "launching nodes" in line or "done launching" in line],
                "pid": ServerProxy(child.uri).get_pid()[0]}
    finally:
        child.handler._shutdown("test over")
        roslaunch.pmon.shutdown_process_monitor(parent_pm)
        parent.shutdown("test over")
        child.shutdown("test over")


def outcome_of_master(uri: str) -> str:
    try:
        ServerProxy(uri).getPid("/t")
        return "answers"
    except OSError:
        return "gone"


if __name__ == "__main__":
    launch_file = sys.argv[1]
    del sys.argv[1:]
    out = io.StringIO()
    try:
        with redirect_stdout(out), redirect_stderr(io.StringIO()):
            answer = launch(launch_file)
    except Exception:
        traceback.print_exc()
        print(out.getvalue(), file=sys.stderr)
        sys.exit(2)
    roslaunch.pmon.pmon_shutdown()
    print(json.dumps(answer, default=repr))
