"""`rviz --stats`'s line: frames shown and frame-timer turns a second since the last report, and
the longest the event loop went without a turn (a stall still going on included, and counted
whole by the report it ends in)."""

from __future__ import annotations

from kame.rviz.stats import FrameStats


def test_a_report_counts_since_the_last_one_and_the_longest_gap_between_turns() -> None:
    stats = FrameStats(10.0)
    for now in (10.1, 10.2, 10.9, 11.0):
        stats.turned(now)
    for _ in range(3):
        stats.frame_shown()
    assert stats.report(12.0) == "rviz stats: 1.5 frames/s drawn, 2.0 turns/s, longest gap 1000 ms"
    stats.turned(12.1)  # the stall the last report saw going on ended 1.1 s after it began
    assert stats.report(13.0) == "rviz stats: 0.0 frames/s drawn, 1.0 turns/s, longest gap 1100 ms"
    assert stats.report(13.5) == "rviz stats: 0.0 frames/s drawn, 0.0 turns/s, longest gap 1400 ms"  # since 12.1
