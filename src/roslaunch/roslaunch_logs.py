"""roslaunch.roslaunch_logs: `roslaunch-logs`: the log directory of the running roscore's run."""

from __future__ import annotations

import os
import sys
from optparse import OptionParser

import rosgraph
import rospkg

__all__ = ["NAME", "get_run_id", "logs_main"]

NAME = "roslaunch-logs"


def get_run_id() -> str | None:
    """The master's /run_id, or None when no master answers."""
    try:
        return str(rosgraph.Master("/roslaunch").getParam("/run_id"))
    except Exception:  # as ROS: any failure to ask the master means there is no run
        return None


def logs_main() -> None:
    parser = OptionParser(usage="usage: %prog", prog=NAME)
    _, args = parser.parse_args()
    if args:
        parser.error(f"{NAME} takes no arguments")
    log_dir = rospkg.get_log_dir()
    if not log_dir:
        print("Cannot determine ROS log directory", file=sys.stderr)
        sys.exit(1)
    run_id = get_run_id()
    if not run_id:
        print("No active roscore", file=sys.stderr)
        print(log_dir)
        sys.exit(2)
    print(os.path.join(log_dir, run_id))
