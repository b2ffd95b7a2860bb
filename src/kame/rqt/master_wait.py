"""Waiting for the master, as rqt does when it starts before roscore: a thread asks the master
for its pid until it answers, then calls `on_up` once (on that thread; a window passes a
queued signal's emit). The waiter owns the thread: `stop()` ends the wait and joins it."""

from __future__ import annotations

import threading
from collections.abc import Callable

from kame.node.master_proxy import MasterError, MasterProxy
from kame.node.remote_poll import poll_remote
from kame.protocol.xmlrpc import XmlRpcError

RETRY = 0.5  # seconds between asks; each ask is also bounded by ASK_TIMEOUT
ASK_TIMEOUT = 2.0


class MasterWaiter:
    def __init__(self, master_uri: str, caller_id: str, on_up: Callable[[], None]) -> None:
        self.master_uri = master_uri
        self.on_up = on_up
        self._master = MasterProxy(master_uri, caller_id, timeout=ASK_TIMEOUT)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._wait, name="rqt-master-wait", daemon=True)
        self._thread.start()

    def _wait(self) -> None:
        def answers() -> bool | None:
            try:
                self._master.call("getPid")
            except (OSError, MasterError, XmlRpcError):
                return None
            return True

        try:
            if poll_remote(answers, self._stop.wait, RETRY):  # stop() ends the wait at once
                self.on_up()
        finally:
            self._master.close()

    def waiting(self) -> bool:
        return self._thread.is_alive()

    def stop(self) -> None:
        self._stop.set()
        self._thread.join()
