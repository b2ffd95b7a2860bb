"""A wait in the main thread that a signal ends, whichever thread the kernel delivered it to.

Linux gives a signal sent to a process to any of its threads that does not block it (a thread
busy on a CPU often takes it before the sleeping main thread does). Python's C-level handler
then only flags the signal for the main thread, which runs the Python handler at its next
bytecode: a main thread blocked in a lock (an Event.wait() without timeout) never gets there,
and Ctrl-C is lost. Python writes each signal to its wakeup fd from whichever thread caught it,
so a main thread waiting in select() on that fd wakes up and runs the handler.
"""

from __future__ import annotations

import os
import select
import signal
import threading
import time
from collections.abc import Callable


class MainThreadWait:
    """Waits of the main thread that end on a condition (after `wake()`) or on any signal."""

    def __init__(self) -> None:
        self._read_fd, self._write_fd = os.pipe()
        os.set_blocking(self._read_fd, False)
        os.set_blocking(self._write_fd, False)  # set_wakeup_fd requires it; a full pipe wakes anyway

    def wake(self) -> None:
        """Make the current wait look at its condition again (from any thread)."""
        try:
            os.write(self._write_fd, b"\0")
        except BlockingIOError:
            pass  # full: the waiter has bytes to read, so it wakes up already

    def wait(self, done: Callable[[], bool], timeout: float | None) -> bool:
        """Wait in the main thread until `done()` (checked at each wake() and signal) or
        `timeout`; True once `done()`. Signal handlers run while it waits, as in any wait."""
        if threading.current_thread() is not threading.main_thread():
            raise RuntimeError("MainThreadWait.wait is for the main thread")
        deadline = None if timeout is None else time.monotonic() + timeout
        previous = signal.set_wakeup_fd(self._write_fd, warn_on_full_buffer=False)
        try:
            while not done():
                left = None if deadline is None else deadline - time.monotonic()
                if left is not None and left <= 0:
                    return False
                ready, _, _ = select.select([self._read_fd], [], [], left)
                if ready:
                    self._drain()
            return True
        finally:
            signal.set_wakeup_fd(previous)

    def _drain(self) -> None:
        try:
            while os.read(self._read_fd, 512):
                pass
        except BlockingIOError:
            pass


_shared: MainThreadWait | None = None
_shared_lock = threading.Lock()


def main_thread_wait() -> MainThreadWait:
    """The process's one MainThreadWait (only the main thread waits in it, one wait at a time)."""
    global _shared
    with _shared_lock:  # made once, whichever thread asks first
        if _shared is None:
            _shared = MainThreadWait()
        return _shared


class SignalSafeEvent(threading.Event):
    """An Event whose wait() in the main thread also lets signal handlers run at once, whichever
    thread the kernel gave the signal to: a tool's Ctrl-C handler that sets its stop event then
    ends the wait. In other threads it waits as any Event does. Setting one wakes the main
    thread's wait, whatever it waits for; that wait looks at its own condition again."""

    def set(self) -> None:
        super().set()
        if _shared is not None:  # made before its waiter first looks at the flag: none missed
            _shared.wake()

    def wait(self, timeout: float | None = None) -> bool:
        if threading.current_thread() is not threading.main_thread():
            return super().wait(timeout)
        return main_thread_wait().wait(self.is_set, timeout)
