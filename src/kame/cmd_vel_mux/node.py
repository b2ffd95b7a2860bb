"""yocs_cmd_vel_mux's node: `rosrun yocs_cmd_vel_mux cmd_vel_mux _yaml_cfg_file:=mux.yaml` (the
TurtleBot's launch files run it as the CmdVelMuxNodelet; kame's runs as a node of that name).

Subscribes each input of ~yaml_cfg_file's `subscribers` (geometry_msgs/Twist, under the node's
namespace: input/teleop is /cmd_vel_mux/input/teleop) and publishes the commands that pass
(kame.cmd_vel_mux.selection) on ~output, and the name of the input that took the output on
~active (std_msgs/String, latched), as yocs's does. Time is the node's ROS time (simulated under
/use_sim_time), as yocs's timers.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import yaml

from geometry_msgs.msg import Twist
from kame.client import log
from kame.client.clock import get_time
from kame.client.process import get_param, init_node, spin
from kame.client.topics import Publisher, Subscriber
from kame.cmd_vel_mux.selection import Input, Mux, MuxConfigError, inputs_from_config
from std_msgs.msg import String


class CmdVelMux:
    def __init__(self, inputs: list[Input]) -> None:
        self.mux = Mux(inputs)
        self.output = Publisher("~output", Twist, queue_size=10)
        self.active = Publisher("~active", String, queue_size=1, latch=True)
        self.active.publish(String("idle"))
        # yocs subscribes with its private NodeHandle: a relative topic is under the node's name
        self.subscribers = [Subscriber(i.topic if i.topic.startswith("/") else f"~{i.topic}", Twist, self._command,
                                       callback_args=index, queue_size=10)
                            for index, i in enumerate(inputs)]

    def _command(self, msg: Any, index: int) -> None:
        before = self.mux.allowed
        if not self.mux.offer(index, get_time()):
            return
        if self.mux.allowed != before:
            self.active.publish(String(self.mux.inputs[index].name))
        self.output.publish(msg)


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    init_node("cmd_vel_mux", argv)
    path = str(get_param("~yaml_cfg_file", ""))
    try:
        inputs = inputs_from_config(yaml.safe_load(Path(path).read_text()))
    except (OSError, yaml.YAMLError, MuxConfigError) as exc:
        log.emit(log.ERROR, "CmdVelMux : yaml_cfg_file [%s] could not be used: %s", (path, exc))
        return 1
    CmdVelMux(inputs)
    spin()
    return 0
