"""kame.cli.topic_stats: the figures and lines of rostopic hz, bw and delay."""

from __future__ import annotations

from kame.cli.topic_stats import BandwidthStats, DelayStats, RateStats, format_rate, format_rate_table


def test_rate_over_a_steady_stream() -> None:
    stats = RateStats()
    for i in range(11):
        assert stats.add(100.0 + i * 0.1) is None
    summary = stats.summary()
    assert summary is not None and summary.window == 11
    assert format_rate(summary) == ("average rate: 10.000\n\tmin: 0.100s max: 0.100s std dev: 0.00000s "
                                    "window: 11")
    assert stats.summary() is None  # nothing new since
    assert format_rate(None) == "no new messages"


def test_rate_window_and_reset() -> None:
    stats = RateStats(window=5)
    for i in range(20):
        stats.add(1.0 + i * (0.1 if i < 15 else 0.2))
    summary = stats.summary()
    assert summary is not None and summary.window == 5 and abs(summary.rate - 5.0) < 1e-6
    assert stats.add(0.0) == "time has reset, resetting counters"
    assert stats.summary() is None


def test_rate_table() -> None:
    a, b = RateStats(), RateStats()
    for i in range(6):
        a.add(1.0 + i * 0.2)
        b.add(1.0 + i * 0.016)
    table = format_rate_table([("/turtle1/pose", a.summary()), ("/slow", None), ("/color", b.summary())])
    lines = table.split("\n")
    assert lines[0].startswith("    topic       rate   min_delta   max_delta   ") and lines[0].endswith(" window")
    assert lines[1] == "=" * len(lines[0])
    assert lines[2].startswith("/turtle1/pose   5.0    0.2 ")
    assert lines[3].startswith("/color          62.5   0.016 ")
    assert lines[2].endswith("   6     ") and table.endswith("\n")
    assert format_rate_table([("/a", None)]) == "no new messages"


def test_bandwidth_units() -> None:
    stats = BandwidthStats()
    assert stats.report(0.0) is None
    for i in range(5):
        stats.add(10.0 + i, 24)
    assert stats.report(15.0) == "average: 24.00B/s\n\tmean: 24.00B min: 24.00B max: 24.00B window: 5"
    big = BandwidthStats(window=2)
    big.add(0.0, 1000)
    big.add(0.5, 3000)
    big.add(0.9, 5000)
    assert big.report(1.0) == "average: 16.00KB/s\n\tmean: 4.00KB min: 3.00KB max: 5.00KB window: 2"
    huge = BandwidthStats()
    huge.add(0.0, 2_000_000)
    huge.add(0.5, 2_000_000)
    assert huge.report(1.0) == "average: 4.00MB/s\n\tmean: 2.00MB min: 2.00MB max: 2.00MB window: 2"


def test_delay() -> None:
    stats = DelayStats()
    stats.add(10.0, 9.0)  # the first message only starts the count
    assert stats.report() is None
    stats.add(10.5, 10.499)
    stats.add(11.0, 10.998)
    assert stats.report() == ("average delay: 0.002\n\tmin: 0.001s max: 0.002s std dev: 0.00050s window: 3")
    assert stats.report() == "no new messages"
