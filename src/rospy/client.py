"""rospy.client: init_node, spin, parameters and the other top-level functions (kame.client.process)."""

from kame.client.process import (
    DEFAULT_MASTER_URI,
    delete_param,
    get_master,
    get_param,
    get_param_cached,
    get_param_names,
    get_published_topics,
    has_param,
    init_node,
    myargv,
    search_param,
    set_param,
    spin,
    wait_for_message,
)

__all__ = [
    "DEFAULT_MASTER_URI",
    "delete_param",
    "get_master",
    "get_param",
    "get_param_cached",
    "get_param_names",
    "get_published_topics",
    "has_param",
    "init_node",
    "myargv",
    "search_param",
    "set_param",
    "spin",
    "wait_for_message",
]
