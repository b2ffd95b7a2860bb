"""rospy.impl.paramserver: the cache of subscribed parameters that get_param_cached answers from."""

from __future__ import annotations

from typing import Any

from kame.client import core

__all__ = ["ParamServerCache", "get_param_server_cache"]


class ParamServerCache:
    """The node's cached parameters (kame's Node keeps them, updated by the master's paramUpdate)."""

    def get(self, key: str) -> Any:
        """The cached value of resolved `key`; KeyError when it is not cached."""
        node = core.get_node()
        if node is None:
            raise KeyError(key)
        return node.param_cache[key]


_cache = ParamServerCache()


def get_param_server_cache() -> ParamServerCache:
    return _cache
