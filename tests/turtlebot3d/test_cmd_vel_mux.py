"""yocs_cmd_vel_mux's rule: the highest-priority commander still talking drives; a lower one waits
until the holder's timeout passes; turtlebot_gazebo's mux.yaml reads."""

from __future__ import annotations

import pytest
import yaml

from kame.cmd_vel_mux.selection import Input, Mux, MuxConfigError, inputs_from_config
from tests.support import REPO

TELEOP, NAVI, SAFETY = 0, 1, 2


def mux() -> Mux:
    return Mux([Input("Teleoperation", "input/teleop", 1.0, 7), Input("Navigation", "input/navi", 1.0, 5),
                Input("Safety", "input/safety_controller", 0.2, 10)])


def test_the_higher_priority_takes_the_output_and_keeps_it_while_it_talks() -> None:
    m = mux()
    assert m.offer(NAVI, 0.0)  # the output is free
    assert m.offer(TELEOP, 0.1)  # higher: takes it
    assert not m.offer(NAVI, 0.2)
    assert m.offer(TELEOP, 1.0)
    assert not m.offer(NAVI, 1.9)  # teleop spoke 0.9 s ago: still its
    assert m.offer(NAVI, 2.1)  # 1.1 s of silence: teleop's timeout passed
    assert m.allowed == NAVI
    assert m.offer(SAFETY, 2.2) and not m.offer(TELEOP, 2.3)
    assert m.offer(TELEOP, 2.5)  # the safety controller's 0.2 s passed


def test_turtlebot_gazebos_mux_yaml_and_bad_configurations() -> None:
    path = REPO / "src" / "kame" / "share" / "turtlebot_gazebo" / "param" / "mux.yaml"
    inputs = inputs_from_config(yaml.safe_load(path.read_text()))
    assert [i.topic for i in inputs] == ["input/safety_controller", "input/teleop", "input/switch", "input/navi",
                                         "/cmd_vel"]
    with pytest.raises(MuxConfigError, match="no 'subscribers' list"):
        inputs_from_config({"publisher": "output"})
    with pytest.raises(MuxConfigError, match="subscriber 0 needs name, topic, timeout and priority"):
        inputs_from_config({"subscribers": [{"name": "a", "topic": "b", "timeout": "soon", "priority": 1}]})
