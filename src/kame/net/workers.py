"""Threads for short blocking jobs (handshakes, one-shot service calls), kept for reuse.

Starting a Python thread costs tens of microseconds; a node that accepts a connection per
service call pays that on every call. Idle workers wait on a queue for the next job and end
after `idle_timeout`; a job that finds no idle worker gets a new one, so long jobs (a
persistent service connection) never hold up short ones. The pool owns its workers: `close()`
ends the idle ones and joins them all (a running job's owner must first end what it waits on).
"""

from __future__ import annotations

import queue
import threading
import time
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
        self._threads: set[threading.Thread] = set()

    def submit(self, job: Callable[[], None]) -> None:
        with self._lock:
            if self._closed:
                return
            self._jobs.put(job)
            if self._idle:
                self._idle -= 1
                return
            worker = threading.Thread(target=self._work, name=self._name, daemon=True)
            self._threads = {t for t in self._threads if t.is_alive()}
            self._threads.add(worker)
            worker.start()  # under the lock: close() never sees a worker that has not started

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

    def close(self, timeout: float = 2.0) -> None:
        """End the idle workers and wait up to `timeout` for every worker to end: the running
        jobs' owners close what those jobs wait on (their sockets) before closing the pool."""
        with self._lock:
            self._closed = True
            idle, self._idle = self._idle, 0
            workers = [t for t in self._threads if t is not threading.current_thread()]
        for _ in range(idle):
            self._jobs.put(_STOP)
        deadline = time.monotonic() + timeout
        for worker in workers:
            worker.join(max(0.0, deadline - time.monotonic()))
