"""rospy.impl.paramserver: the cache of subscribed parameters, as rospy's tree of namespaces.

The process's cache (get_param_server_cache()) is also the node's: what kame's node caches
(get_param_cached's subscribeParam, the master's paramUpdate) is found by get(), and set()
and delete() change what get_param_cached answers.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from kame.client import core
from rospy.names import GLOBALNS, SEP

__all__ = ["GLOBALNS", "SEP", "ParamServerCache", "get_param_server_cache"]


def _path(key: str) -> list[str]:
    return [part for part in key.split(SEP) if part]


class ParamServerCache:
    """Cached parameter values in a tree of dictionaries, keyed by resolved names."""

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.d: dict[str, Any] | None = None
        self.notifier: Callable[[str, Any], None] | None = None
        self._node_cache: Callable[[], dict[str, Any] | None] = lambda: None

    def set_notifier(self, notifier: Callable[[str, Any], None]) -> None:
        """`notifier(key, value)` is told of each update()."""
        self.notifier = notifier

    def set(self, key: str, value: Any) -> None:
        """Cache `value` at `key` (a dictionary at `/` replaces the whole tree)."""
        with self.lock:
            if key == GLOBALNS:
                if type(value) is not dict:
                    raise TypeError("cannot set root of parameter tree to non-dictionary")
                self.d = value
            else:
                *namespaces, value_key = _path(key)
                if self.d is None:
                    self.d = {}
                tree = self.d
                for ns in namespaces:
                    if type(tree.get(ns)) is not dict:
                        tree[ns] = {}
                    tree = tree[ns]
                tree[value_key] = value
            node_cache = self._node_cache()
            if node_cache is not None:
                node_cache[key] = value

    def update(self, key: str, value: Any) -> None:
        """Change the cached `key` to `value` and tell the notifier; KeyError if it is not cached."""
        with self.lock:
            node_cache = self._node_cache()
            try:
                self._tree_update(key, value)
            except KeyError:
                if node_cache is None or key not in node_cache:
                    raise
            if node_cache is not None and key in node_cache:
                node_cache[key] = value
            if self.notifier is not None:
                self.notifier(key, value)

    def _tree_update(self, key: str, value: Any) -> None:
        *namespaces, value_key = _path(key)
        tree = self.d
        if tree is None:
            raise KeyError(key)
        for ns in namespaces:
            if ns not in tree:
                raise KeyError(key)
            tree = tree[ns]
        if value_key not in tree:
            raise KeyError(key)
        tree[value_key] = value

    def delete(self, key: str) -> None:
        """Forget the cached `key`; KeyError if it is not cached or is the root."""
        with self.lock:
            if key == GLOBALNS:
                raise KeyError("cannot delete root of parameter tree")
            if self.d is None:
                raise KeyError(key)
            *namespaces, value_key = _path(key)
            tree = self.d
            for ns in namespaces:
                if type(tree) is not dict or ns not in tree:
                    raise KeyError(key)
                tree = tree[ns]
            if value_key not in tree:
                raise KeyError(key)
            del tree[value_key]
            node_cache = self._node_cache()
            if node_cache is not None:
                node_cache.pop(key, None)

    def get(self, key: str) -> Any:
        """The cached value at `key` (a subtree for a namespace); KeyError when it is not cached."""
        with self.lock:
            try:
                return self._tree_get(key)
            except KeyError:
                node_cache = self._node_cache()
                if node_cache is None or key not in node_cache:
                    raise
                return node_cache[key]

    def _tree_get(self, key: str) -> Any:
        if self.d is None:
            raise KeyError(key)
        val: Any = self.d
        if key != GLOBALNS:
            for ns in _path(key):
                if type(val) is not dict:
                    raise KeyError(val)
                val = val[ns]
        if isinstance(val, dict) and not val:
            raise KeyError(key)
        return val


def _process_node_cache() -> dict[str, Any] | None:
    node = core.get_node()
    return node.param_cache if node is not None else None


_param_server_cache: ParamServerCache | None = None


def get_param_server_cache() -> ParamServerCache:
    """The process's cache, shared with its node's."""
    global _param_server_cache
    if _param_server_cache is None:
        _param_server_cache = ParamServerCache()
        _param_server_cache._node_cache = _process_node_cache
    return _param_server_cache
