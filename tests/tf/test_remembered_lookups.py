"""The buffer core remembers successful lookups; these tests prove a remembered answer is never
stale: new data on any link the lookup read, a parent change, data aged out of the cache,
clear(), a replaced static transform, a frame above the old root. And a random script of
inserts and lookups gives, step by step, what a core that never saw a lookup before gives."""

from __future__ import annotations

import math
import random
from typing import Any

import pytest

from kame.tf import errors
from kame.tf.buffer_core import BufferCore, Transform

S = 10**9
IDENTITY = (0.0, 0.0, 0.0, 1.0)


def yaw(angle: float) -> tuple[float, float, float, float]:
    return (0.0, 0.0, math.sin(angle / 2), math.cos(angle / 2))


def put(core: BufferCore, parent: str, child: str, stamp: int, x: float, angle: float = 0.0,
        static: bool = False) -> None:
    assert core.set_transform(Transform(parent, child, stamp, (x, 0.0, 0.0), yaw(angle)), "/test", static) is None


def chain_core() -> BufferCore:
    core = BufferCore()
    for stamp in (1 * S, 2 * S):
        put(core, "map", "odom", stamp, 1.0)
        put(core, "odom", "base", stamp, 2.0)
        put(core, "base", "laser", stamp, 3.0)
    return core


def test_new_data_on_a_middle_link_changes_the_latest_answer() -> None:
    core = chain_core()
    first = core.lookup_transform("map", "laser", 0)
    assert core.lookup_transform("map", "laser", 0) is first  # remembered
    assert (first.stamp, first.translation[0]) == (2 * S, 6.0)
    put(core, "odom", "base", 3 * S, 20.0)
    assert core.lookup_transform("map", "laser", 0) == first  # the common time is still 2 s
    put(core, "map", "odom", 3 * S, 1.0)
    put(core, "base", "laser", 3 * S, 3.0)
    now = core.lookup_transform("map", "laser", 0)
    assert (now.stamp, now.translation[0]) == (3 * S, 24.0)


def test_a_stamp_inserted_between_two_changes_the_interpolation() -> None:
    core = chain_core()
    halfway = 1500 * 10**6
    assert core.lookup_transform("map", "laser", halfway).translation[0] == pytest.approx(6.0)
    put(core, "odom", "base", 1600 * 10**6, 12.0)  # out of order, between 1 s and 2 s
    moved = 1.0 + 2.0 + 10.0 * 5 / 6 + 3.0  # odom->base now 2 at 1 s, 12 at 1.6 s
    assert core.lookup_transform("map", "laser", halfway).translation[0] == pytest.approx(moved)
    assert core.can_transform("map", "laser", halfway) == (True, "")


def test_a_new_parent_changes_the_path() -> None:
    core = chain_core()
    assert core.lookup_transform("map", "laser", 0).translation[0] == pytest.approx(6.0)
    put(core, "map", "base", 3 * S, 100.0)  # base now hangs off map directly
    put(core, "base", "laser", 3 * S, 3.0)
    assert core.lookup_transform("map", "laser", 0).translation[0] == pytest.approx(103.0)
    assert core.chain("map", "laser") == ["laser", "base", "map"]


def test_a_link_that_set_the_common_time_but_is_not_on_the_path_at_that_time() -> None:
    core = BufferCore()
    put(core, "map", "arm", 9 * S, 1.0)
    put(core, "map", "hand", 9 * S, 2.0)  # hand hangs off map at 9 s ...
    put(core, "arm", "hand", 9500 * 10**6, 3.0)  # ... and off arm from 9.5 s on
    # the common time goes up hand's newest parent (arm, newest at 9 s); at 9 s hand's parent is map
    first = core.lookup_transform("map", "hand", 0)
    assert (first.stamp, first.translation[0]) == (9 * S, 2.0)
    put(core, "map", "arm", 9500 * 10**6, 1.0)  # arm, not read by the walk at 9 s, moves the common time
    now = core.lookup_transform("map", "hand", 0)
    assert (now.stamp, now.translation[0]) == (9500 * 10**6, 4.0)


def test_data_aged_out_of_the_cache_is_gone_from_remembered_answers() -> None:
    core = chain_core()
    assert core.lookup_transform("map", "laser", 1 * S).stamp == 1 * S
    for link in (("map", "odom"), ("odom", "base"), ("base", "laser")):
        put(core, *link, 30 * S, 1.0)
    with pytest.raises(errors.ExtrapolationException, match=r"only time 30\.000000000 is in the buffer"):
        core.lookup_transform("map", "laser", 1 * S)
    assert core.can_transform("map", "laser", 1 * S)[0] is False


def test_clear_forgets_remembered_answers_and_a_new_static_replaces_the_old() -> None:
    core = chain_core()
    put(core, "laser", "lens", 0, 0.5, static=True)
    assert core.lookup_transform("map", "lens", 0).translation[0] == pytest.approx(6.5)
    put(core, "laser", "lens", 0, 0.25, static=True)
    assert core.lookup_transform("map", "lens", 0).translation[0] == pytest.approx(6.25)
    assert core.lookup_transform("laser", "lens", 0).translation[0] == pytest.approx(0.25)
    core.clear()
    with pytest.raises(errors.TransformException):
        core.lookup_transform("map", "lens", 0)
    assert core.lookup_transform("laser", "lens", 0).translation[0] == pytest.approx(0.25)  # static stays


def outcome(core: BufferCore, target: str, source: str, stamp: int) -> Any:
    try:
        found = core.lookup_transform(target, source, stamp)
    except errors.TransformException as exc:
        return type(exc).__name__, str(exc)
    return found.parent, found.child, found.stamp, found.translation, found.rotation


def test_a_random_script_answers_as_a_core_that_remembers_nothing() -> None:
    rng = random.Random(17)
    frames = ["f0", "f1", "f2", "f3", "f4", "f5"]
    core = BufferCore(cache_time=3 * S)
    inserts: list[tuple[Transform, bool]] = []
    checked = 0
    for _ in range(600):
        if rng.random() < 0.4:
            child = rng.choice(frames[1:])
            parent = rng.choice(frames[:frames.index(child)])  # parents come earlier: no loops
            static = child == "f5"
            transform = Transform(parent, child, 0 if static else rng.randrange(1, 20) * S // 2,
                                  (rng.uniform(-1, 1), rng.uniform(-1, 1), 0.0), yaw(rng.uniform(-3, 3)))
            if core.set_transform(transform, "/random", static) is None:
                inserts.append((transform, static))
            continue
        target, source = rng.sample(frames, 2)
        stamp = rng.choice([0, rng.randrange(1, 40) * S // 4])
        fresh = BufferCore(cache_time=3 * S)
        for transform, static in inserts:
            fresh.set_transform(transform, "/random", static)
        for _ in range(2):  # the second ask may be answered from memory
            assert outcome(core, target, source, stamp) == outcome(fresh, target, source, stamp)
        checked += 1
    assert checked > 300
