"""Time and Duration: canonical values and genpy's arithmetic."""

from __future__ import annotations

import pickle

import pytest

from kame.rostime import Duration, Time


def test_canonical_form() -> None:
    assert (Duration(0, -500_000_000).secs, Duration(0, -500_000_000).nsecs) == (-1, 500_000_000)
    assert (Time(1, 2_500_000_000).secs, Time(1, 2_500_000_000).nsecs) == (3, 500_000_000)
    assert Time(1.5) == Time(1, 500_000_000)
    assert Duration.from_sec(-0.25) == Duration(0, -250_000_000)
    assert Time.from_nsec(1_000_000_007) == Time(1, 7)


def test_negative_time_and_float_with_nsecs_are_refused() -> None:
    with pytest.raises(TypeError):
        Time(-1)
    with pytest.raises(ValueError):
        Time(1.5, 3)


def test_arithmetic() -> None:
    t = Time(10, 0)
    d = Duration(1, 500_000_000)
    assert t + d == Time(11, 500_000_000) == d + t
    assert (t + d) - t == d
    assert t - d == Time(8, 500_000_000)
    assert d * 2 == Duration(3)
    assert d * 0.5 == Duration(0, 750_000_000)
    assert Duration(3) / 2 == Duration(1, 500_000_000)
    assert Duration(3) / Duration(1, 500_000_000) == 2.0
    assert Duration(7) // Duration(2) == 3
    assert Duration(7) % Duration(2) == Duration(1)
    assert divmod(Duration(7), Duration(2)) == (3, Duration(1))
    assert -d == Duration(-2, 500_000_000)
    assert abs(Duration(-2)) == Duration(2)
    with pytest.raises(TypeError):
        _ = t + t  # type: ignore[operator]


def test_comparison_and_values() -> None:
    assert Time(1, 5) < Time(2) <= Time(2) and Time(3) > Time(2, 999_999_999)
    assert Time(1) != Duration(1)
    with pytest.raises(TypeError):
        _ = Time(1) < Duration(1)
    assert Time(1, 500_000_000).to_sec() == 1.5
    assert Time(1, 5).to_nsec() == 1_000_000_005
    assert not Time() and Duration(0, 1)
    assert str(Time(1, 5)) == "1000000005"
    assert repr(Time(1, 5)) == "genpy.Time[1000000005]"
    assert repr(Duration(-1)) == "genpy.Duration[-1000000000]"
    assert hash(Time(1, 2)) == hash(Time(1, 2))
    assert pickle.loads(pickle.dumps(Duration(-3, 7))) == Duration(-3, 7)
