"""rospy.impl.init: the node's default ports and master URI, and start_node, which starts a
node's XML-RPC and TCPROS servers: a kame Node, owned by the caller (its shutdown() stops it);
it registers nothing by itself and is not the process's node (init_node makes that one).
RosStreamHandler is rosgraph.roslogging's, loaded when asked for."""

from __future__ import annotations

import os
from typing import Any

from kame import environ
from kame.node.config import node_config
from kame.node.node import Node
from rospy.core import _lazy_names, is_shutdown, rospyerr, signal_shutdown
from rospy.impl.masterslave import ROSHandler
from rospy.impl.tcpros import init_tcpros

__all__ = ["DEFAULT_MASTER_PORT", "DEFAULT_MASTER_URI", "DEFAULT_NODE_PORT", "ROSHandler", "init_tcpros",
           "is_shutdown", "rospyerr", "signal_shutdown", "start_node"]

DEFAULT_NODE_PORT = 0  # bind to any open port
DEFAULT_MASTER_PORT = 11311
DEFAULT_MASTER_URI = environ.DEFAULT_MASTER_URI


def start_node(environ: Any, resolved_name: str, master_uri: str | None = None, port: int = 0,
               tcpros_port: int = 0) -> Node:
    """A node named `resolved_name` serving its XML-RPC API on `port` and TCPROS on
    `tcpros_port` (0: any free port), for the master at `master_uri` (default: `environ`'s)."""
    env = dict(os.environ if environ is None else environ)
    if master_uri:
        env["ROS_MASTER_URI"] = master_uri
    namespace, _, base = resolved_name.rstrip("/").rpartition("/")
    env["ROS_NAMESPACE"] = namespace or "/"
    return Node(node_config(base, {}, env, xmlrpc_port=port, tcpros_port=tcpros_port))


__getattr__ = _lazy_names(__name__, {"RosStreamHandler": ("rosgraph.roslogging", "RosStreamHandler")})
