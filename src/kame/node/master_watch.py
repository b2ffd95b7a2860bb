"""Noticing a restarted master and registering with it again (beyond ROS 1).

ROS 1 nodes register once: after `roscore` restarts, running nodes are unknown to the new
master, so `rosnode list` misses them and new subscribers never find their publishers. A node
here asks the master's getPid every WATCH_INTERVAL seconds; when the PID changes, or the master
answers again after failing to, the node registers everything again: the parameters it set,
its parameter subscriptions, services, publications and subscriptions (each subscription takes
the new master's publisher list, as from a publisherUpdate).
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable

from kame.node.master_proxy import MasterError, MasterProxy

log = logging.getLogger("kame.node")

WATCH_INTERVAL = 0.5  # s: with the master's own start-up, nodes are back within 2 s of a restart


class MasterWatch:
    """Owned by a Node: `run` is its thread's target, `close` ends it at once."""

    def __init__(self, master_uri: str, caller_id: str, register_again: Callable[[], None],
                 interval: float = WATCH_INTERVAL) -> None:
        # its own connection: a check waiting on a master that went away holds up no other call
        self._master = MasterProxy(master_uri, caller_id)
        self._register_again = register_again
        self._interval = interval
        self._closing = threading.Event()
        self.pid: int | None = None  # the master's, when it last answered
        self._lost = False  # the last call failed

    def run(self) -> None:
        try:
            while not self._closing.is_set():
                self.check()
                self._closing.wait(self._interval)
        finally:
            self._master.close()

    def check(self) -> None:
        try:
            pid = int(self._master.call("getPid", timeout=self._interval * 2))
        except (OSError, MasterError, ValueError, TypeError):
            if not self._lost:
                log.debug("the master at %s does not answer", self._master.uri)
            self._lost = True
            return
        came_back = self._lost or (self.pid is not None and pid != self.pid)
        self.pid, self._lost = pid, False
        if came_back and not self._closing.is_set():
            log.info("the master at %s is back (pid %d): registering again", self._master.uri, pid)
            try:
                self._register_again()
            except (OSError, MasterError) as exc:
                log.warning("registering again with the master at %s failed: %s", self._master.uri, exc)
                self._lost = True  # try again at the next check

    def close(self) -> None:
        self._closing.set()
