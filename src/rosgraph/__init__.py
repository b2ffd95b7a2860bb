"""rosgraph, ROS 1's library of graph names, master access and network rules, over kame."""

from __future__ import annotations

import sys
from collections.abc import Sequence

from . import names
from .masterapi import Master, MasterError, MasterException, MasterFailure
from .masterapi import is_online as is_master_online
from .rosenv import ROS_HOSTNAME, ROS_IP, ROS_IPV6, ROS_MASTER_URI, ROS_NAMESPACE, get_master_uri

__all__ = ["ROS_HOSTNAME", "ROS_IP", "ROS_IPV6", "ROS_MASTER_URI", "ROS_NAMESPACE", "Master", "MasterError",
           "MasterException", "MasterFailure", "get_master_uri", "is_master_online", "myargv", "names"]


def myargv(argv: Sequence[str] | None = None) -> list[str]:
    """argv (default sys.argv) without the ROS remapping arguments (anything with `:=`)."""
    return [a for a in (sys.argv if argv is None else argv) if names.REMAP not in a]
