"""What the node-running tools (rosbag record/play, rosout) share: their node, named from the
command line's special arguments as rospy names a node, and a stop event set by Ctrl-C,
SIGTERM or a master's shutdown request.

A tool waits for "this happened, or we were stopped" in one wait (wait_until): whatever makes
its condition true calls notify(), and stopping notifies too, so no wait polls."""

from __future__ import annotations

import os
import signal
from collections.abc import Callable, Mapping
from typing import Any

from kame import environ
from kame.net.signal_wake import SignalSafeEvent
from kame.node.config import node_config
from kame.node.master_proxy import MasterError
from kame.node.node import Node
from kame.node.remote_poll import poll_remote

# A master that is not up yet sends no event: it is asked again five times a second.
MASTER_POLL_PERIOD = 0.2


class ToolNode:
    """`__name`, `__ns`, `__master`, `__ip`/`__hostname` and remappings applied; the node is
    created, not yet registered with anything."""

    def __init__(self, special: Mapping[str, str], default_name: str,
                 remappings: Mapping[str, str] | None = None) -> None:
        config = node_config(default_name, special, os.environ, remappings)
        self.namespace = environ.namespace(os.environ, special)
        self.caller_id = config.name
        # waited on by the main thread: events a signal caught by any thread still ends
        self.stop = SignalSafeEvent()
        self._changed = SignalSafeEvent()  # set by notify(); wait_until clears it before looking

        def on_signal(signum: int, frame: Any) -> None:
            self.request_stop()

        signal.signal(signal.SIGINT, on_signal)
        signal.signal(signal.SIGTERM, on_signal)
        self.node = Node(config)
        self.node.on_shutdown_request = lambda reason: self.request_stop()

    def request_stop(self) -> None:
        self.stop.set()
        self.notify()

    def notify(self) -> None:
        """Something a wait_until condition reads has changed."""
        self._changed.set()

    def wait_until(self, ready: Callable[[], bool]) -> bool:
        """Until ready() (True) or the tool is stopped (False); what makes ready() true calls notify()."""
        while not (self.stop.is_set() or ready()):
            self._changed.wait()
            self._changed.clear()  # a notify() after this is seen by the next look or wait
        return not self.stop.is_set()

    def wait_for_master(self) -> bool:
        """Until the master answers (True), or the tool is stopped first (False)."""
        def answers() -> bool | None:
            try:
                self.node.master.call("getPid", timeout=2.0)
            except (OSError, MasterError):
                return None
            return True

        return poll_remote(answers, self.stop.wait, MASTER_POLL_PERIOD) is not None
