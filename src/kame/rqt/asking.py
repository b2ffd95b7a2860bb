"""A window whose calls to ROS run on its one worker thread, never on the window's thread: a
hung node or service costs a status line ("waiting for ..."), not a frozen window.

Rules: `_ask(what, call, then)` runs `call` on the worker; `then(answer)` runs on the window's
thread when the answer is back (through `answered`, a queued signal). What `call` may raise
(`failures`) is shown in the status line instead. `idle` says every call asked so far has been
answered. `close_worker()` (closing the window calls it) joins the worker: at most one call's
timeout.
"""

from __future__ import annotations

from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import Any, ClassVar

from PySide6.QtCore import Signal
from PySide6.QtGui import QCloseEvent
from PySide6.QtWidgets import QLabel, QWidget


@dataclass(frozen=True)
class _Failed:
    text: str


class AskingWindow(QWidget):
    answered = Signal(object)  # (what to do with the answer, the answer or _Failed)
    idle = Signal()  # every call asked so far has been answered
    failures: ClassVar[tuple[type[BaseException], ...]] = ()  # what a call may raise
    waiting: ClassVar[str] = "waiting for {}..."  # the status line while a call is out

    def __init__(self, thread_name: str) -> None:
        super().__init__()
        self.status = QLabel("")
        self._worker: ThreadPoolExecutor | None = ThreadPoolExecutor(max_workers=1, thread_name_prefix=thread_name)
        self._asked = 0
        self.answered.connect(self._on_answer)

    def _ask(self, what: str, call: Callable[[], Any], then: Callable[[Any], None]) -> None:
        """Run `call` on the worker; `then(answer)` runs on the window's thread when it is back."""
        if self._worker is None:
            return
        self._asked += 1
        self.status.setText(self.waiting.format(what))

        def job() -> None:
            try:
                answer = call()
            except self.failures as exc:
                answer = _Failed(str(exc))
            self.answered.emit((then, answer))

        self._worker.submit(job)

    def _on_answer(self, pair: tuple[Callable[[Any], None], Any]) -> None:
        then, answer = pair
        self._asked -= 1
        if isinstance(answer, _Failed):
            self.status.setText(answer.text)
        else:
            then(answer)
        if self._asked == 0:
            self.idle.emit()

    def busy(self) -> bool:
        return self._asked > 0

    def close_worker(self) -> None:
        if self._worker is not None:
            self._worker.shutdown(wait=True, cancel_futures=True)
            self._worker = None

    def closeEvent(self, event: QCloseEvent) -> None:
        self.close_worker()
        super().closeEvent(event)
