"""One message of a topic, read with kame's rostopic, for the simulator tests."""

from __future__ import annotations

from typing import Any

import yaml

from tests.turtlesim.sim import Sim


def echo(sim: Sim, topic: str, *args: str) -> dict[str, Any]:
    out = sim.run("rostopic", "echo", "-n", "1", *args, topic, timeout=20).stdout
    data = yaml.safe_load(out.split("---")[0])
    assert isinstance(data, dict), out
    return data
