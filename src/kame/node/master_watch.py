"""Noticing a restarted master and registering with it again (beyond ROS 1).

ROS 1 nodes register once: after `roscore` restarts, running nodes are unknown to the new
master, so `rosnode list` misses them and new subscribers never find their publishers. A node
here asks the master every WATCH_INTERVAL seconds who it is (lookupNode of its own name); when
the master answers that it does not know the node although the node has registered something,
the master is a new one, and the node registers everything again: the parameters it set, its
parameter subscriptions, services, publications and subscriptions (each subscription takes the
new master's publisher list, as from a publisherUpdate).

Asking about the node itself, rather than comparing the master's PID, also sees a master
restarted under the same PID (PID 1 in a container), and a slow answer is never taken for a
restart. A node that registered nothing has nothing to restore.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable

from kame.node.master_proxy import MasterError, MasterProxy
from kame.protocol.xmlrpc import XmlRpcError

log = logging.getLogger("kame.node")

WATCH_INTERVAL = 0.5  # s: with the master's own start-up, nodes are back within 2 s of a restart


class MasterWatch:
    """Owned by a Node: `run` is its thread's target, `close` ends it at once."""

    def __init__(self, master_uri: str, name: str, registered: Callable[[], bool],
                 register_again: Callable[[], None], interval: float = WATCH_INTERVAL) -> None:
        # its own connection: a check waiting on a master that went away holds up no other call
        self._master = MasterProxy(master_uri, name)
        self._name = name
        self._registered = registered
        self._register_again = register_again
        self._interval = interval
        self._closing = threading.Event()
        self._answering = True

    def run(self) -> None:
        try:
            while not self._closing.wait(self._interval):
                self.check()
        finally:
            self._master.close()

    def check(self) -> None:
        if not self._registered():
            return
        try:
            self._master.call("lookupNode", self._name, timeout=self._interval * 2)
            self._answering = True
            return
        except MasterError:
            pass  # a master that does not know us
        except (OSError, XmlRpcError) as exc:
            if self._answering:
                log.debug("the master at %s does not answer: %s", self._master.uri, exc)
            self._answering = False
            return
        self._answering = True
        if self._closing.is_set():
            return
        log.info("the master at %s does not know %s (it restarted): registering again", self._master.uri,
                 self._name)
        try:
            self._register_again()
        except (OSError, MasterError) as exc:
            log.warning("registering again with the master at %s failed: %s", self._master.uri, exc)

    def close(self) -> None:
        self._closing.set()
