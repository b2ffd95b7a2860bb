"""The node an rqt tool runs as: `/rqt_<tool>_<pid>` (rqt_graph hides `/rqt*` as debug), on the
master of `__master:=`, else ROS_MASTER_URI, with `__ip`/`__hostname` and ROS_IP/ROS_HOSTNAME
honoured as every ROS program does. The caller owns the node and shuts it down."""

from __future__ import annotations

import os
from collections.abc import Mapping

from kame import environ
from kame.net.address import host_addresses
from kame.node.node import Node, NodeConfig


def master_uri(special: Mapping[str, str], env: Mapping[str, str] | None = None) -> str:
    return environ.master_uri(os.environ if env is None else env, special)


def start_node(tool: str, special: Mapping[str, str], env: Mapping[str, str] | None = None) -> Node:
    env = os.environ if env is None else env
    host = host_addresses(env, special)
    name = f"/rqt_{tool}_{os.getpid()}"
    return Node(NodeConfig(name, master_uri(special, env), host.advertised, host.bind))
