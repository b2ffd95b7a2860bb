"""A node's configuration from its command line and environment, as every ROS 1 client reads it.

The name is `__name:=` or the program's own, under `__ns:=` / ROS_NAMESPACE; the master is
`__master:=` / ROS_MASTER_URI (kame.environ); the advertised and bound addresses follow
rosgraph.network (kame.net.address); remappings are resolved against the node's name.
"""

from __future__ import annotations

from collections.abc import Mapping

from kame import environ, names
from kame.net.address import host_addresses
from kame.node.node import NodeConfig


def node_config(name: str, special: Mapping[str, str], env: Mapping[str, str],
                remappings: Mapping[str, str] | None = None, xmlrpc_port: int = 0,
                tcpros_port: int = 0) -> NodeConfig:
    """`name` is the node's base name when there is no `__name:=`."""
    caller_id = names.canonicalize(environ.namespace(env, special) + special.get("name", name))
    host = host_addresses(env, special)
    resolved = names.resolve_remappings(remappings, caller_id) if remappings else {}
    return NodeConfig(caller_id, environ.master_uri(env, special), host.advertised, host.bind,
                      remappings=tuple(resolved.items()), xmlrpc_port=xmlrpc_port, tcpros_port=tcpros_port)
