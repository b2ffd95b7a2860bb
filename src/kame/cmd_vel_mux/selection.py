"""yocs_cmd_vel_mux's rule, without ROS or a clock: which input's command is passed on.

An input that sends is active until `timeout` seconds pass without a command from it. A command
passes when no input holds the output, when its input holds it, or when its input's priority is
above the holder's (then it takes the output). The holder lets go when its timeout passes
(yocs's timer; here noticed at the next command, which is when it matters).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any


class MuxConfigError(ValueError):
    """A subscribers list yocs_cmd_vel_mux would refuse; the text says which entry and why."""


@dataclass(frozen=True)
class Input:
    name: str
    topic: str
    timeout: float
    priority: int


def inputs_from_config(config: Any) -> list[Input]:
    """The `subscribers` list of a yaml_cfg_file (name, topic, timeout, priority each)."""
    entries = config.get("subscribers") if isinstance(config, dict) else None
    if not isinstance(entries, list) or not entries:
        raise MuxConfigError("the configuration has no 'subscribers' list")
    inputs = []
    for number, entry in enumerate(entries):
        try:
            inputs.append(Input(str(entry["name"]), str(entry["topic"]), float(entry["timeout"]),
                                int(entry["priority"])))
        except (KeyError, TypeError, ValueError) as exc:
            raise MuxConfigError(f"subscriber {number} needs name, topic, timeout and priority ({exc})") from exc
    return inputs


class Mux:
    def __init__(self, inputs: list[Input]) -> None:
        self.inputs = inputs
        self.allowed: int | None = None
        self._last: dict[int, float] = {}

    def offer(self, index: int, now: float) -> bool:
        """A command from input `index` at time `now`: True when it is to be published."""
        held = self.allowed
        if held is not None and held != index and now - self._last.get(held, now) > self.inputs[held].timeout:
            self.allowed = held = None
        self._last[index] = now
        if held is None or held == index or self.inputs[index].priority > self.inputs[held].priority:
            self.allowed = index
            return True
        return False
