"""Where a ROS process finds its master and its namespace: the one reading of ROS_MASTER_URI,
ROS_NAMESPACE and the `__master:=` / `__ns:=` arguments that every kame program shares.

A special argument (parsed by kame.names.parse_args) wins over the variable; an empty value
counts as unset; the namespace is made global (`ns` -> `/ns/`).
"""

from __future__ import annotations

from collections.abc import Mapping

from kame import names

DEFAULT_MASTER_URI = "http://localhost:11311/"  # rosgraph's, for a node when nothing names a master
SETUP_MASTER_URI = "http://localhost:11311"  # what ROS's setup files export and roslaunch prints


def master_uri(env: Mapping[str, str], special: Mapping[str, str] | None = None,
               default: str = DEFAULT_MASTER_URI) -> str:
    return (special or {}).get("master") or env.get("ROS_MASTER_URI") or default


def namespace(env: Mapping[str, str], special: Mapping[str, str] | None = None) -> str:
    return names.make_global_ns((special or {}).get("ns") or env.get("ROS_NAMESPACE") or "/")
