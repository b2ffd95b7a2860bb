"""roslaunch.scriptapi.ROSLaunch: start nodes from a Python program.

    launch = roslaunch.scriptapi.ROSLaunch()
    launch.start()
    process = launch.launch(roslaunch.core.Node("rospy_tutorials", "talker"))
    ...
    process.stop(); launch.stop()
"""

from __future__ import annotations

from kame.cli.roslaunch import get_or_generate_uuid
from kame.launch.errors import LaunchError
from roslaunch.core import Node
from roslaunch.parent import Process, ROSLaunchParent


class ROSLaunch:
    def __init__(self) -> None:
        self.parent = ROSLaunchParent(get_or_generate_uuid(None, False), [], is_core=False, show_summary=False)
        self.started = False

    def start(self) -> None:
        self.parent.start(auto_terminate=False)
        self.started = True

    def launch(self, node: Node) -> Process:
        if not self.started:
            raise LaunchError("please start ROSLaunch first")
        if not isinstance(node, Node):
            raise ValueError("arg must be of type Node")
        process, success = self.parent.runner.launch_node(node)
        if not success or process is None:
            raise LaunchError(f"failed to launch {node.package}/{node.type}")
        return process

    def spin(self) -> None:
        self.parent.spin()

    def spin_once(self) -> None:
        self.parent.spin_once()

    def stop(self) -> None:
        self.parent.shutdown()
