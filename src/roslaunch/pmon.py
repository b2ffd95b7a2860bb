"""roslaunch.pmon: what scripts use of roslaunch's process monitor: ProcessListener (pass one to
ROSLaunchParent(process_listeners=[...]) to hear of each process that dies) and the launch
exceptions. kame's supervisor (kame.launch.supervisor) watches the processes."""

from __future__ import annotations

from roslaunch.core import RLException

__all__ = ["FatalProcessLaunch", "NonFatalProcessLaunch", "ProcessListener"]


class FatalProcessLaunch(RLException):
    """A process that must run (a core one) could not start."""


class NonFatalProcessLaunch(RLException):
    """A process could not start; the launch goes on."""


class ProcessListener:
    """Told of each process of a launch that dies (whether or not it is respawned)."""

    def process_died(self, process_name: str, exit_code: int | None) -> None:
        """`process_name` (`talker-2`) ended with `exit_code` (None: killed without one)."""
