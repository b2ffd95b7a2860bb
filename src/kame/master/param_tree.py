"""The parameter server's tree and which subscribers hear about a change.

Rules (ros1-interop spec §4; rosmaster 1.15.15 paramserver.py):
- A dict value is a namespace: setParam with a dict replaces the whole subtree; setting below a
  scalar turns the scalar into a dict; setting a scalar drops the children. Only dicts are
  namespaces (a dict inside a list is just data). The root must stay a dict.
- Keys arrive resolved (global, canonical). Empty path segments are ignored on lookup.
- getParamNames lists leaves only, so an empty dict has no name although hasParam sees it.
- searchParam starts in the caller's *private* namespace and matches on the key's first segment.
- Whatever is stored can be sent back: setParam refuses (unstorable) integers outside XML-RPC's
  32-bit range and a tree deeper than MAX_TREE_DEPTH (key segments plus value nesting), which
  the XML-RPC encoder or a reader would fault on, so getParam('/') always answers.
- Subscriptions are stored under `<key>/`. On a change, a subscriber at or above the changed key
  gets the new value under the changed key; subscribers below a dict that was set get their new
  sub-value, or `{}` if their key vanished; a deletion is reported as `{}`. Only setParam skips
  the caller: rosmaster passes the caller only on that path, so a deleting node is notified.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from kame.master.notifications import ParamUpdate
from kame.names import SEP, canonicalize, is_global, is_private, ns_join
from kame.protocol.xmlrpc import Value

#: Deepest the tree may be (key segments plus nesting of the value): XML-RPC readers bound
#: nesting (kame's at 256 elements, about 80 levels), and the whole tree must go out as one value.
MAX_TREE_DEPTH = 64
_MIN_INT = -(2**31)
_MAX_INT = 2**31 - 1


def unstorable(key: str, value: Value) -> str | None:
    """Why `value` cannot be stored at `key` (a reply to getParam would fault), or None.
    Iterative: a hostile value cannot exhaust the stack here."""
    pending: list[tuple[Value, int]] = [(value, len(_segments(key)))]
    while pending:
        item, depth = pending.pop()
        if type(item) is int and not _MIN_INT <= item <= _MAX_INT:
            return (f"cannot set parameter [{key}]: {item!r} does not fit a 32-bit signed integer "
                    "(int exceeds XML-RPC limits)")
        if isinstance(item, (dict, list)):
            if depth >= MAX_TREE_DEPTH:
                return (f"cannot set parameter [{key}]: the parameter tree would nest more than "
                        f"{MAX_TREE_DEPTH} levels deep")
            children = item.values() if isinstance(item, dict) else item
            pending.extend((child, depth + 1) for child in children)
    return None


def _segments(key: str) -> list[str]:
    return [s for s in key.split(SEP) if s]


class ParamTree:
    def __init__(self) -> None:
        self._root: dict[str, Value] = {}

    def get(self, key: str) -> Value:
        """The value at `key` (a dict for a namespace). Raises KeyError if unset."""
        value: Value = self._root
        for seg in _segments(key):
            if type(value) is not dict:
                raise KeyError(key)
            value = value[seg]
        return value

    def has(self, key: str) -> bool:
        try:
            self.get(key)
        except KeyError:
            return False
        return True

    def set(self, key: str, value: Value) -> None:
        """Raises TypeError when asked to set the root to something other than a dict."""
        segments = _segments(key)
        if not segments:
            if type(value) is not dict:
                raise TypeError("cannot set root of parameter tree to non-dictionary")
            self._root = value
            return
        d = self._root
        for seg in segments[:-1]:
            child = d.get(seg)
            if type(child) is not dict:
                child = d[seg] = {}
            d = child
        d[segments[-1]] = value

    def delete(self, key: str) -> None:
        """Raises KeyError if unset; the root cannot be deleted."""
        segments = _segments(key)
        if not segments:
            raise KeyError("cannot delete root of parameter tree")
        d: Value = self._root
        for seg in segments[:-1]:
            if type(d) is not dict or seg not in d:
                raise KeyError(key)
            d = d[seg]
        # rosmaster does not check that the parent is a dict here, so deleting below a scalar
        # fails with Python's own TypeError (-1 "Error: invalid arguments: ..."); we do the same.
        parent: Any = d
        if segments[-1] not in parent:
            raise KeyError(key)
        del parent[segments[-1]]

    def names(self) -> list[str]:
        """Full names of all leaf values (empty dicts have none), depth first in insertion order."""
        out: list[str] = []
        _leaf_names(SEP, self._root, out)
        return out

    def search(self, caller_id: str, key: str) -> str | None:
        """searchParam: the full key found by an upwards search from the caller's private namespace.

        Raises ValueError for a private or empty key, or a caller_id that is not global.
        """
        if not key or is_private(key):
            raise ValueError("invalid key")
        if not is_global(caller_id):
            raise ValueError("namespace must be global")
        if is_global(key):
            return key if self.has(key) else None
        head = _segments(key)[0]
        if self.has(ns_join(caller_id, head)):
            return ns_join(caller_id, key)
        namespaces = _segments(caller_id)
        for i in range(1, len(namespaces) + 1):
            parents = namespaces[:-i]
            if self.has(SEP + SEP.join([*parents, head])):
                return SEP + SEP.join([*parents, key])
        return None


def _leaf_names(prefix: str, d: dict[str, Value], out: list[str]) -> None:
    for k, v in d.items():
        full = ns_join(prefix, k)
        if type(v) is dict:
            _leaf_names(full, v, out)
        else:
            out.append(full)


def subscription_key(key: str) -> str:
    """How subscriptions are stored: canonical key plus a trailing slash (`/` stays `/`)."""
    return key if key == SEP else canonicalize(key) + SEP


def param_updates(
    subscribers: Mapping[str, Mapping[str, str]], key: str, value: Value, skip_caller: str | None = None
) -> list[ParamUpdate]:
    """The paramUpdate calls that setting `key` to `value` implies (`{}` for a deletion).

    `subscribers` maps subscribed keys (with trailing slash) to {caller_id: caller_api}.
    `skip_caller` is left out of the updates at or above `key` (setParam's own caller).
    """
    if not subscribers:
        return []
    changed = subscription_key(key)
    below: dict[str, Value] | None = None
    if type(value) is dict:
        below = {}
        _keys_below(changed, value, below)
    updates: list[ParamUpdate] = []
    for sub_key, regs in subscribers.items():
        ns_key = sub_key if sub_key.endswith(SEP) else sub_key + SEP
        if changed.startswith(ns_key):
            updates.extend(ParamUpdate(api, changed, value) for cid, api in regs.items()
                           if cid != skip_caller)
        elif below is not None and ns_key.startswith(changed) and sub_key not in below:
            updates.extend(ParamUpdate(api, sub_key, {}) for api in regs.values())
    if below:
        for sub_key, sub_value in below.items():
            listeners = subscribers.get(sub_key)
            if listeners:
                updates.extend(ParamUpdate(api, sub_key, sub_value) for api in listeners.values())
    return updates


def _keys_below(prefix: str, value: Mapping[str, Value], out: dict[str, Value]) -> None:
    # Every key inside a dict that was set, with a trailing slash, mapped to its new value.
    for k, v in value.items():
        full = ns_join(prefix, k) + SEP
        out[full] = v
        if type(v) is dict:
            _keys_below(full, v, out)
