"""message_filters: kame's against Debian's real package on the same input sequences, and the
Subscriber on a live topic."""

from __future__ import annotations

import random
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

import message_filters
from message_filters import ApproximateTimeSynchronizer, Cache, SimpleFilter, TimeSynchronizer

from ..support import Proc, free_port, kame_command, ros_env, running, wait_for_master
from . import debian
from .filters_driver import Stamped, run

DRIVER = Path(__file__).with_name("filters_driver.py")
NODE = Path(__file__).with_name("filters_node.py")


def random_events(rng: random.Random, inputs: int, count: int, spread_ns: int) -> list[list[int]]:
    """Arrivals on random inputs, stamps near a moving base with jitter, some out of order."""
    events = []
    for step in range(count):
        stamp_ns = 10**9 + step * spread_ns // 3 + rng.randrange(-spread_ns, spread_ns)
        if rng.random() < 0.3:  # an exact copy of a recent stamp: the exact synchronizer's case
            stamp_ns = 10**9 + (step // 2) * spread_ns
        events.append([rng.randrange(inputs), stamp_ns // 10**9, stamp_ns % 10**9])
    return events


def requests() -> list[dict[str, Any]]:
    rng = random.Random(20)
    cases: list[dict[str, Any]] = []
    for inputs in (2, 3):
        for queue_size in (1, 3, 10):
            for spread_ns in (1_000_000, 50_000_000):
                events = random_events(rng, inputs, 300, spread_ns)
                cases.append({"kind": "exact", "inputs": inputs, "queue_size": queue_size, "events": events})
                for slop in (0.001, 0.02, 0.1):
                    cases.append({"kind": "approx", "inputs": inputs, "queue_size": queue_size, "slop": slop,
                                  "events": events})
    for cache_size in (1, 5, 50):
        events = random_events(rng, 1, 80, 50_000_000)
        starts = [1 + rng.randrange(3) for _ in range(30)]
        queries = [[secs, rng.randrange(10**9), secs + rng.randrange(2)] for secs in starts]
        cases.append({"kind": "cache", "inputs": 1, "queue_size": cache_size, "events": events, "queries": queries})
    return cases


@pytest.mark.skipif(not debian.has("message_filters"), reason="Debian's python3-message-filters is not installed")
def test_same_callbacks_as_debian_on_random_sequences() -> None:
    cases = requests()
    theirs = debian.run(DRIVER, cases)
    ours = [run(case) for case in cases]
    assert sum(len(answer["delivered"]) for answer in theirs) > 1000  # the cases do synchronize
    for case, mine, reference in zip(cases, ours, theirs, strict=True):
        assert mine == reference, {k: v for k, v in case.items() if k != "events"}


def test_exact_synchronizer_waits_for_every_input() -> None:
    import rospy.rostime
    rospy.rostime.set_rostime_initialized(True)
    a, b = SimpleFilter(), SimpleFilter()
    got: list[tuple[int, ...]] = []
    TimeSynchronizer([a, b], 10).registerCallback(lambda x, y, tag: got.append((x.ident, y.ident, tag)), "t")
    a.signalMessage(Stamped(1, 5, 0))
    b.signalMessage(Stamped(2, 5, 1))
    assert got == []
    b.signalMessage(Stamped(3, 5, 0))
    assert got == [(1, 3, "t")]


class Plain:
    def __init__(self, ident: int) -> None:
        self.ident = ident


def test_headerless_messages_need_allow_headerless() -> None:
    import rospy.rostime
    rospy.rostime.set_rostime_initialized(True)
    a, b = SimpleFilter(), SimpleFilter()
    got: list[tuple[int, int]] = []
    strict = ApproximateTimeSynchronizer([a, b], 5, 0.5)
    strict.registerCallback(lambda x, y: got.append((x.ident, y.ident)))
    a.signalMessage(Plain(1))
    b.signalMessage(Plain(2))
    assert got == [] and strict.queues == [{}, {}]
    c, d = SimpleFilter(), SimpleFilter()
    ApproximateTimeSynchronizer([c, d], 5, 0.5, allow_headerless=True).registerCallback(
        lambda x, y: got.append((x.ident, y.ident)))
    c.signalMessage(Plain(3))
    d.signalMessage(Plain(4))  # stamped with ROS time now: well within half a second
    assert got == [(3, 4)]


def test_chained_cache_feeds_a_synchronizer() -> None:
    import rospy.rostime
    rospy.rostime.set_rostime_initialized(True)
    a, b = SimpleFilter(), SimpleFilter()
    cache = Cache(a, 3)
    got: list[tuple[int, int]] = []
    TimeSynchronizer([cache, b], 5).registerCallback(lambda x, y: got.append((x.ident, y.ident)))
    for ident in range(5):
        a.signalMessage(Stamped(ident, 1, ident))
    b.signalMessage(Stamped(9, 1, 4))
    assert got == [(4, 9)]
    assert [m.ident for m in cache.cache_msgs] == [2, 3, 4]
    assert message_filters.Cache is Cache


@pytest.fixture(scope="module")
def master_env(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, str]]:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    environment = ros_env(Path(tmp_path_factory.mktemp("filters")), uri)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), environment)
    try:
        wait_for_master(uri, proc=master)
        yield environment
    finally:
        master.stop()


def synced_pairs(subscriber: list[str], env: dict[str, str]) -> list[tuple[float, float]]:
    with running([sys.executable, str(NODE), "pub"], env):
        sub = Proc([*subscriber, str(NODE), "sub"], env)
        try:
            sub.popen.wait(60)
        finally:
            out, err = sub.stop()
    assert sub.popen.returncode == 0, out + err
    assert "topics left /right" in out
    return [(float(x), float(y)) for line in out.splitlines() if line.startswith("synced")
            for x, y in [line.split()[1:]]]


def test_subscribers_synchronize_a_live_kame_publisher(master_env: dict[str, str]) -> None:
    pairs = synced_pairs([sys.executable], master_env)
    assert len(pairs) == 3 and all(y == x + 0.5 for x, y in pairs)


@pytest.mark.skipif(not debian.has("message_filters", "rospy", "geometry_msgs.msg"),
                    reason="Debian's rospy and python3-message-filters are not installed")
def test_debians_message_filters_synchronize_a_kame_publisher(master_env: dict[str, str]) -> None:
    pairs = synced_pairs([str(debian.SYSTEM_PYTHON)], master_env)
    assert len(pairs) == 3 and all(y == x + 0.5 for x, y in pairs)
