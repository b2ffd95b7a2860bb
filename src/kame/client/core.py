"""The process-wide state of a program's node: the one Node, shutdown and its hooks, and names.

kame.client (and the CLI entry points) are the only holders of process-wide state; kame's Node
underneath is an explicit object.
"""

from __future__ import annotations

import atexit
import contextlib
import logging
import os
import sys
import threading
from collections.abc import Callable, Iterator
from typing import Any

from kame import environ, names
from kame.arity import accepts
from kame.client.errors import ROSInitException
from kame.net.signal_wake import main_thread_wait
from kame.node.node import Node

_node: Node | None = None
# before init_node, as rospy: the namespace of `__ns:=` or ROS_NAMESPACE, and a caller ID in it
_namespace = environ.namespace(os.environ, names.parse_args(sys.argv).special)
_caller_id = names.ns_join(_namespace, "unnamed")
_remappings: dict[str, str] = {}
_shutdown = threading.Event()
_shutdown_requested = threading.Event()  # set as signal_shutdown starts, before the pre-shutdown hooks
_node_down = threading.Event()  # set once signal_shutdown has unregistered and closed the node
_shutdown_reason = ""
_shutdown_hooks: list[Callable[..., Any]] = []
_preshutdown_hooks: list[Callable[..., Any]] = []
_client_shutdown_hooks: list[Callable[..., Any]] = []  # run first (rospy's client hooks: its on_shutdown)
_hooks_lock = threading.Lock()
_initialized = False

log = logging.getLogger("rospy.core")


_deferred: list[Callable[[Node], None]] = []


def defer_until_initialized(action: Callable[[Node], None]) -> None:
    with _hooks_lock:
        if _node is None:
            _deferred.append(action)
            return
    action(_node)


def run_deferred() -> None:
    """Bind the topics and services created before init_node() (called by init_node)."""
    with _hooks_lock:
        actions, _deferred[:] = list(_deferred), []
    assert _node is not None
    for action in actions:
        action(_node)


def get_node() -> Node | None:
    return _node


def set_node(node: Node, caller_id: str, namespace: str, remappings: dict[str, str]) -> None:
    global _node, _caller_id, _namespace, _remappings, _initialized
    _node = node
    _caller_id = caller_id
    _namespace = namespace
    _remappings = remappings
    _initialized = True


def is_initialized() -> bool:
    return _initialized


def set_initialized(initialized: bool) -> None:
    """What is_initialized answers from now on (init_node sets it)."""
    global _initialized
    _initialized = initialized


def set_remappings(remappings: dict[str, str]) -> None:
    """The resolved remappings resolve_name applies from now on (init_node sets them)."""
    global _remappings
    _remappings = dict(remappings)


def get_caller_id() -> str:
    return _caller_id


def get_name() -> str:
    return _caller_id


def get_namespace() -> str:
    return _namespace


def get_node_uri() -> str | None:
    return _node.uri if _node is not None else None


def resolve_name(name: str, caller_id: str | None = None) -> str:
    """Resolve a name for this node (or `caller_id`), remappings applied."""
    return names.resolve(name, caller_id or _caller_id, _remappings)


def remap_name(name: str, caller_id: str | None = None) -> str:
    resolved = names.resolve(name, caller_id or _caller_id)
    return _remappings.get(resolved, name)


def is_shutdown() -> bool:
    return _shutdown.is_set()


def is_shutdown_requested() -> bool:
    """True from the moment signal_shutdown starts (while the pre-shutdown hooks run, before is_shutdown)."""
    return _shutdown_requested.is_set()


_main_waiting = 0  # >0 while the main thread blocks in one of our waits
_wakers: set[threading.Event] = set()  # events that shutdown sets (woken_at_shutdown)


def wait_for_shutdown(timeout: float | None) -> bool:
    """Wait up to `timeout` for shutdown; True once it happened. A signal wakes it at once."""
    global _main_waiting
    if threading.current_thread() is not threading.main_thread():
        return _shutdown.wait(timeout)
    # Not _shutdown.wait(): a SIGINT that the kernel gives to another thread would not end
    # that wait, so its handler (which starts the shutdown) would never run (see MainThreadWait).
    _main_waiting += 1
    try:
        return main_thread_wait().wait(_shutdown.is_set, timeout)
    finally:
        _main_waiting -= 1


@contextlib.contextmanager
def woken_at_shutdown(event: threading.Event) -> Iterator[None]:
    """Within the block, shutdown sets `event` too (at once if it already happened): a wait
    for "this event or shutdown" is then one wait on `event`, not a poll of both."""
    with _hooks_lock:
        _wakers.add(event)
        if _shutdown.is_set():
            event.set()
    try:
        yield
    finally:
        with _hooks_lock:
            _wakers.discard(event)


def main_thread_is_waiting() -> bool:
    return _main_waiting > 0


@contextlib.contextmanager
def main_thread_waiting() -> Iterator[None]:
    """Mark the main thread as waiting while it runs someone else's loop (e.g. Qt's exec) that
    watches `is_shutdown()`: Ctrl-C then shuts the node down instead of raising
    ROSInterruptException into that loop's callbacks (where it could only be printed)."""
    global _main_waiting
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    _main_waiting += 1
    try:
        yield
    finally:
        _main_waiting -= 1


def on_shutdown(hook: Callable[..., Any]) -> None:
    """Run `hook` (with no argument, or the reason) when the node shuts down."""
    with _hooks_lock:
        if _shutdown.is_set():
            _call_hook(hook, _shutdown_reason)
            return
        _shutdown_hooks.append(hook)


def _add_hook(hook: Callable[..., Any], hooks: list[Callable[..., Any]], with_reason: bool) -> None:
    if not callable(hook):
        raise TypeError(f"shutdown hook [{hook}] must be a function or callable object: {type(hook)}")
    with _hooks_lock:
        if not _shutdown.is_set():
            hooks.append(hook)
            return
    log.warning("a shutdown hook was added after shutdown")
    if with_reason:
        hook("already shutdown")
    else:
        _call_client_hook(hook, "already shutdown")


def add_preshutdown_hook(hook: Callable[[str], Any]) -> None:
    """Run `hook(reason)` as shutdown starts, before is_shutdown() is true (it may still publish)."""
    _add_hook(hook, _preshutdown_hooks, with_reason=True)


def add_shutdown_hook(hook: Callable[[str], Any]) -> None:
    """Run `hook(reason)` once is_shutdown() is true, before the node unregisters."""
    _add_hook(hook, _shutdown_hooks, with_reason=True)


def add_client_shutdown_hook(hook: Callable[..., Any]) -> None:
    """Run `hook()` (or `hook(reason)`, if it takes one) first when shutdown starts, before the
    pre-shutdown hooks and while is_shutdown() is still false: rospy's on_shutdown."""
    _add_hook(hook, _client_shutdown_hooks, with_reason=False)


def _call_hook(hook: Callable[..., Any], reason: str) -> None:
    try:
        if accepts(hook, 1):
            hook(reason)
        else:
            hook()
    except Exception:
        log.exception("shutdown hook %s failed", hook)


def _call_client_hook(hook: Callable[..., Any], reason: str) -> None:
    """`hook()` as rospy calls its on_shutdown hooks; `hook(reason)` for one that needs an argument."""
    try:
        if accepts(hook, 0):
            hook()
        else:
            hook(reason)
    except Exception:
        log.exception("shutdown hook %s failed", hook)


def signal_shutdown(reason: str) -> None:
    """Shut the node down: hooks run, everything is unregistered, waits are interrupted."""
    global _shutdown_reason
    with _hooks_lock:
        if _shutdown_requested.is_set():
            return
        _shutdown_reason = reason
        _shutdown_requested.set()
        client, _client_shutdown_hooks[:] = list(_client_shutdown_hooks), []
        pre, _preshutdown_hooks[:] = list(_preshutdown_hooks), []
    for client_hook in client:
        _call_client_hook(client_hook, reason)
    for hook in pre:
        _call_hook(hook, reason)
    with _hooks_lock:
        _shutdown.set()
        for waker in _wakers:
            waker.set()
        main_thread_wait().wake()
    with _hooks_lock:
        hooks, _shutdown_hooks[:] = list(_shutdown_hooks), []
    for hook in hooks:
        _call_hook(hook, reason)
    if _node is not None:
        _node.shutdown(reason)
    _node_down.set()


def _at_exit() -> None:
    """rospy's atexit hook: unregister before the interpreter goes, and let a shutdown that
    another thread started (e.g. `rosnode kill`) finish unregistering instead of dying with it."""
    signal_shutdown("atexit")
    _node_down.wait(5.0)


atexit.register(_at_exit)


def get_remappings() -> dict[str, str]:
    """The node's name remappings, both sides resolved (empty before init_node)."""
    return dict(_remappings)


def spin() -> None:
    """Block until the node is shut down (Ctrl-C, rosnode kill, signal_shutdown)."""
    if not is_initialized():
        raise ROSInitException("client code must call rospy.init_node() first")
    try:
        wait_for_shutdown(None)
    except KeyboardInterrupt:
        signal_shutdown("keyboard interrupt")
