"""A child process fed the newest of a stream of values on its stdin: what a simulation hands
its window when the window lives in a process of its own, so that a window that dies (its X
server gone, a native crash) cannot take the simulation with it.

Rules:
- `offer()` never blocks: it replaces the value waiting to be written, so a child that falls
  behind sees fewer values, never old ones. The writer thread encodes a value when it takes it.
- The feed owns its two threads (writer, exit watcher) and its child: `close()` ends the
  child's input (EOF), waits for it to exit, kills it by its PID if it does not, and joins both.
- The child's exit that we did not ask for is reported once, with its status, to `on_exit`.
"""

from __future__ import annotations

import subprocess
import threading
from collections.abc import Callable, Mapping, Sequence
from typing import Generic, TypeVar

T = TypeVar("T")
_NOTHING = object()


class ChildFeed(Generic[T]):
    def __init__(self, args: Sequence[str], encode: Callable[[T], bytes], on_exit: Callable[[int], None],
                 env: Mapping[str, str] | None = None) -> None:
        """Start `args` (in a session of its own: a terminal's Ctrl-C is for its feeder, which
        then ends it). `on_exit(returncode)` runs on the watcher thread."""
        self._encode = encode
        self._on_exit = on_exit
        self._wake = threading.Condition()
        self._pending: object = _NOTHING
        self._closing = False  # no more writes
        self._closed_by_us = False
        self._child = subprocess.Popen(list(args), stdin=subprocess.PIPE, env=dict(env) if env is not None else None,
                                       start_new_session=True)
        self._writer = threading.Thread(target=self._write, name="child-feed-writer", daemon=True)
        self._watcher = threading.Thread(target=self._watch, name="child-feed-watcher", daemon=True)
        self._writer.start()
        self._watcher.start()

    @property
    def pid(self) -> int:
        return self._child.pid

    def offer(self, value: T) -> None:
        with self._wake:
            if self._closing:
                return
            self._pending = value
            self._wake.notify()

    def close(self, timeout: float = 5.0) -> None:
        with self._wake:
            self._closed_by_us = True
            self._closing = True
            self._wake.notify()
        self._writer.join(timeout)
        if self._writer.is_alive():  # blocked writing to a child that reads no more
            self._child.kill()
            self._writer.join()
        try:
            if self._child.stdin is not None:
                self._child.stdin.close()  # EOF: the child ends
        except OSError:
            pass
        try:
            self._child.wait(timeout)
        except subprocess.TimeoutExpired:
            self._child.kill()
            self._child.wait()
        self._watcher.join()

    def _write(self) -> None:
        stream = self._child.stdin
        assert stream is not None
        while True:
            with self._wake:
                while self._pending is _NOTHING and not self._closing:
                    self._wake.wait()
                if self._closing:
                    return
                value, self._pending = self._pending, _NOTHING
            try:
                stream.write(self._encode(value))  # type: ignore[arg-type]
                stream.flush()
            except OSError:  # the child is gone: the watcher says so
                with self._wake:
                    self._closing = True
                return

    def _watch(self) -> None:
        status = self._child.wait()
        with self._wake:
            asked = self._closed_by_us
            self._closing = True
            self._wake.notify()
        if not asked:
            self._on_exit(status)
