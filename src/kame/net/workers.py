"""Threads for short blocking jobs (handshakes, one-shot service calls), kept for reuse.

Starting a Python thread costs tens of microseconds; a node that accepts a connection per
service call pays that on every call. Idle workers wait on a queue for the next job and end
after `idle_timeout`; a job that finds no idle worker gets a new one, so long jobs (a
persistent service connection) never hold up short ones.
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Callable

_STOP = None


class WorkerPool:
    def __init__(self, name: str, idle_timeout: float = 30.0) -> None:
        self._name = name
        self._idle_timeout = idle_timeout
        self._jobs: queue.SimpleQueue[Callable[[], None] | None] = queue.SimpleQueue()
        self._lock = threading.Lock()
        self._idle = 0
        self._closed = False

    def submit(self, job: Callable[[], None]) -> None:
        with self._lock:
            if self._closed:
                return
            start_one = self._idle == 0
            if not start_one:
                self._idle -= 1
        self._jobs.put(job)
        if start_one:
            threading.Thread(target=self._work, name=self._name, daemon=True).start()

    def _work(self) -> None:
        while True:
            try:
                job = self._jobs.get(timeout=self._idle_timeout)
            except queue.Empty:
                with self._lock:
                    if self._idle > 0 and self._jobs.empty():
                        self._idle -= 1
                        return
                continue
            if job is _STOP:
                return
            try:
                job()
            except Exception:  # a job's own errors are its owner's to log; the worker goes on
                pass
            with self._lock:
                if self._closed:
                    return
                self._idle += 1

    def close(self) -> None:
        """Idle workers end; running jobs finish on their own (their owners close their sockets)."""
        with self._lock:
            self._closed = True
            idle, self._idle = self._idle, 0
        for _ in range(idle):
            self._jobs.put(_STOP)
