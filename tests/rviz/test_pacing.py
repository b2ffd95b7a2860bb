"""When rviz's window takes a frame (kame.rviz.pacing): soon after the source's decoding thread
says a message is ready, not at the next tick of the frame rate, yet never more than one frame
per period however many messages come; and what KAME_RVIZ_STATS writes (kame.rviz.shown_log)."""

from __future__ import annotations

import io
import itertools
import threading
import time
from typing import Any

import pytest

pytest.importorskip("PySide6")

from kame.rviz.shown_log import ShownLog, from_environment, stamp_of
from sensor_msgs.msg import PointCloud2
from visualization_msgs.msg import Marker, MarkerArray


def _pacer(rate: int, took: bool = True) -> tuple[Any, list[float]]:
    """A pacer whose every frame takes messages (`took`) or none, each frame's time noted."""
    from PySide6.QtWidgets import QApplication

    from kame.rviz.pacing import FramePacer

    frames: list[float] = []

    def frame() -> bool:
        frames.append(time.monotonic())
        return took

    return FramePacer(QApplication.instance(), frame, rate), frames


def _from_a_thread(emit: Any, times: int = 1, stop: threading.Event | None = None) -> threading.Thread:
    """Emits as the source's decoding thread does: from a thread that is not Qt's."""
    def run() -> None:
        for _ in range(times):
            if stop is not None and stop.is_set():
                return
            emit()
            time.sleep(0.001)
    thread = threading.Thread(target=run)
    thread.start()
    return thread


def test_a_message_is_taken_without_waiting_for_the_frame_rate(qtbot: Any) -> None:
    pacer, frames = _pacer(30)
    pacer.timer.setInterval(600_000)  # no tick comes within the test: a frame now is the message's
    pacer.timer.start()
    _from_a_thread(pacer.ready.emit).join()
    qtbot.waitUntil(lambda: len(frames) == 1, timeout=60_000)
    pacer.stop()


def test_a_frame_that_took_nothing_holds_no_message_back(qtbot: Any) -> None:
    """The frame rate's ticks find nothing new most of the time: a message after one is taken at
    once, not a period after the tick (which, at 30 ticks a second, would be every message's wait)."""
    pacer, frames = _pacer(30, took=False)
    pacer.timer.setInterval(600_000)
    pacer.timer.start()
    pacer.ready.emit()
    qtbot.waitUntil(lambda: len(frames) == 1, timeout=60_000)
    pacer.ready.emit()  # a period after a frame that took messages would be 10 minutes away
    qtbot.waitUntil(lambda: len(frames) == 2, timeout=60_000)
    pacer.stop()


def test_messages_coalesce_into_at_most_one_frame_a_period(qtbot: Any) -> None:
    pacer, frames = _pacer(10)  # 100 ms
    stop = threading.Event()
    thread = _from_a_thread(pacer.ready.emit, times=100_000, stop=stop)  # a message every ms or so
    try:
        qtbot.waitUntil(lambda: len(frames) >= 8, timeout=60_000)
    finally:
        stop.set()
        thread.join()
    pacer.stop()
    gaps = [later - earlier for earlier, later in itertools.pairwise(frames)]
    assert min(gaps) >= 0.09, gaps  # Qt's coarse timers may fire 5 % early


def test_a_stopped_pacer_leaves_frames_to_its_owner(qtbot: Any) -> None:
    """The tests and the in-process bench stop the timer and draw each frame themselves."""
    pacer, frames = _pacer(1000)
    pacer.stop()
    pacer.ready.emit()
    qtbot.wait(100)  # a frame asked for would have come within its 1 ms period
    assert frames == []


def _stamped_cloud(secs: int, nsecs: int) -> Any:
    cloud = PointCloud2()
    cloud.header.stamp.secs, cloud.header.stamp.nsecs = secs, nsecs
    return cloud


def test_the_shown_log_writes_each_stamped_message_when_its_frame_is_swapped() -> None:
    out = io.StringIO()
    log = ShownLog(out)
    marker = Marker()
    marker.header.stamp.secs = 1_700_000_000
    log.taken({"/markers": [MarkerArray(markers=[marker])], "/cloud": [_stamped_cloud(1_700_000_001, 500_000_000)],
               "/unstamped": [PointCloud2(), MarkerArray()]})
    assert out.getvalue() == ""  # taken, not yet on the screen
    before = time.time()
    log.swapped()
    lines = [line.split() for line in out.getvalue().splitlines()]
    assert [(topic, float(stamp)) for topic, stamp, _, _ in lines] == [("/markers", 1_700_000_000.0),
                                                                      ("/cloud", 1_700_000_001.5)]
    for _, _, taken, shown in lines:
        assert float(taken) <= before <= float(shown)
    log.swapped()  # a later frame shows nothing new
    assert len(out.getvalue().splitlines()) == 2


def test_stamps_and_the_environment_variable(tmp_path: Any) -> None:
    assert stamp_of(_stamped_cloud(3, 250_000_000)) == 3.25
    assert stamp_of(MarkerArray()) is None
    assert from_environment({}) is None
    log = from_environment({"KAME_RVIZ_STATS": str(tmp_path / "shown")})
    assert log is not None
    log.taken({"/cloud": [_stamped_cloud(5, 0)]})
    log.swapped()
    assert (tmp_path / "shown").read_text().split()[:2] == ["/cloud", "5.000000"]  # line-buffered: there already
