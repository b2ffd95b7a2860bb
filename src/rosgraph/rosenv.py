"""rosgraph.rosenv: the ROS environment variables' names and where the master is."""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping, Sequence

from kame.environ import DEFAULT_MASTER_URI

ROS_MASTER_URI = "ROS_MASTER_URI"
ROS_IP = "ROS_IP"
ROS_IPV6 = "ROS_IPV6"
ROS_HOSTNAME = "ROS_HOSTNAME"
ROS_NAMESPACE = "ROS_NAMESPACE"
DEFAULT_MASTER_PORT = 11311

__all__ = ["DEFAULT_MASTER_PORT", "DEFAULT_MASTER_URI", "ROS_HOSTNAME", "ROS_IP", "ROS_IPV6", "ROS_MASTER_URI",
           "ROS_NAMESPACE", "get_master_uri"]


def get_master_uri(env: Mapping[str, str] | None = None, argv: Sequence[str] | None = None) -> str:
    """The `__master:=` argument, else ROS_MASTER_URI, else http://localhost:11311/.

    ValueError for a `__master:=` argument with no value.
    """
    env = os.environ if env is None else env
    argv = sys.argv if argv is None else argv
    for arg in argv:
        if arg.startswith("__master:="):
            parts = arg.split(":=")
            value = parts[1] if len(parts) == 2 else ""
            if not value:
                raise ValueError(f"__master remapping argument '{arg}' improperly specified")
            return value
    return env.get(ROS_MASTER_URI, DEFAULT_MASTER_URI)
