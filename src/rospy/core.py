"""rospy.core: the process's node, shutdown and names (kame.client.core)."""

from kame.client.core import (
    add_preshutdown_hook,
    get_caller_id,
    get_name,
    get_namespace,
    get_node,
    get_node_uri,
    is_initialized,
    is_shutdown,
    is_shutdown_requested,
    on_shutdown,
    remap_name,
    resolve_name,
    signal_shutdown,
    wait_for_shutdown,
)

__all__ = [
    "add_preshutdown_hook",
    "get_caller_id",
    "get_name",
    "get_namespace",
    "get_node",
    "get_node_uri",
    "is_initialized",
    "is_shutdown",
    "is_shutdown_requested",
    "on_shutdown",
    "remap_name",
    "resolve_name",
    "signal_shutdown",
    "wait_for_shutdown",
]
