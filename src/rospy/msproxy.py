"""rospy.msproxy: MasterProxy, the master's XML-RPC API called as this node (its caller ID added,
names resolved), and the parameter server as a dictionary, as rospy's. Calls go through
rospy.core.xmlrpcapi (kame's XML-RPC client)."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from threading import Lock
from typing import Any

from kame.client.errors import ROSException
from rospy import core, names
from rospy.impl import paramserver

__all__ = ["Lock", "MasterProxy"]

# the arguments (after the caller ID) that are names, resolved before the call
_master_arg_remap = {method: [0] for method in (
    "deleteParam", "setParam", "getParam", "searchParam", "subscribeParam", "unsubscribeParam", "hasParam",
    "registerService", "lookupService", "unregisterService", "registerSubscriber", "unregisterSubscriber",
    "registerPublisher", "unregisterPublisher", "lookupNode", "getPublishedTopics")}


class MasterProxy:
    """The master at `uri`: `proxy.getPid()` returns [code, message, value]; `proxy['/p']`
    reads a parameter (KeyError if unset), `proxy['/p'] = v` sets it, `del`, `in` and iteration."""

    def __init__(self, uri: str) -> None:
        self.target = core.xmlrpcapi(uri)

    def __getattr__(self, key: str) -> Callable[..., Any]:
        if key.startswith("__"):
            raise AttributeError(key)
        from rospy.impl.masterslave import ROSHandler

        remappings = _master_arg_remap.get(key) or ROSHandler.remappings(key)

        def call(*args: Any, **kwargs: Any) -> Any:
            full = [names.get_caller_id(), *args]
            for index in remappings:
                full[index + 1] = names.resolve_name(full[index + 1])
            return getattr(self.target, key)(*full, **kwargs)

        return call

    def __getitem__(self, key: str) -> Any:
        resolved_key = names.resolve_name(key)
        try:
            return paramserver.get_param_server_cache().get(resolved_key)
        except KeyError:
            pass
        code, _msg, value = self.target.getParam(names.get_caller_id(), resolved_key)  # type: ignore[union-attr]
        if code != 1:
            raise KeyError(key)
        return value

    def __setitem__(self, key: str, val: Any) -> None:
        resolved_key = names.resolve_name(key)
        self.target.setParam(names.get_caller_id(), resolved_key, val)  # type: ignore[union-attr]
        try:
            paramserver.get_param_server_cache().update(resolved_key, val)
        except KeyError:
            pass

    def search_param(self, key: str) -> str | None:
        mappings = names.get_mappings()
        key = mappings.get(key, key)
        code, msg, val = self.target.searchParam(names.get_caller_id(), key)  # type: ignore[union-attr]
        if code == 1:
            return str(val)
        if code == -1:
            return None
        raise ROSException(f"cannot search for parameter: {msg}")

    def get_param_cached(self, key: str) -> Any:
        resolved_key = names.resolve_name(key)
        cache = paramserver.get_param_server_cache()
        try:
            return cache.get(resolved_key)
        except KeyError:
            code, _msg, value = self.target.subscribeParam(  # type: ignore[union-attr]
                names.get_caller_id(), core.get_node_uri(), resolved_key)
            if code != 1:
                raise KeyError(key) from None
            cache.set(resolved_key, value)
            if isinstance(value, dict) and not value:
                raise KeyError(key) from None
            return value

    def __delitem__(self, key: str) -> None:
        code, msg, _ = self.target.deleteParam(names.get_caller_id(), names.resolve_name(key))  # type: ignore[union-attr]
        if code == -1:
            raise KeyError(key)
        if code != 1:
            raise ROSException(f"cannot delete parameter: {msg}")

    def __contains__(self, key: object) -> bool:
        code, msg, value = self.target.hasParam(  # type: ignore[union-attr]
            names.get_caller_id(), names.resolve_name(str(key)))
        if code != 1:
            raise ROSException(f"cannot check parameter on server: {msg}")
        return bool(value)

    def __iter__(self) -> Iterator[str]:
        code, msg, value = self.target.getParamNames(names.get_caller_id())  # type: ignore[union-attr]
        if code == 1:
            return iter(value)
        raise ROSException(f"cannot retrieve parameter names: {msg}")
