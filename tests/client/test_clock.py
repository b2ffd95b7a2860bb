"""kame.client.clock beyond what rospy exposes: an event woken at each change of simulated time,
which the waits on ROS time (rospy.sleep, an action client's wait_for_server) wait on."""

from __future__ import annotations

import threading
from collections.abc import Iterator

import pytest

from kame import rostime
from kame.client import clock


@pytest.fixture
def sim_time() -> Iterator[None]:
    before = clock._sim_time
    try:
        yield
    finally:
        clock.set_sim_time(before)


@pytest.mark.usefixtures("sim_time")
def test_each_change_of_simulated_time_sets_the_event_within_the_block_only() -> None:
    event = threading.Event()
    with clock.woken_at_change(event):
        clock.set_sim_time(rostime.Time(5))
        assert event.is_set()
        event.clear()
        clock.set_sim_time(None)  # back to the wall clock is a change too
        assert event.is_set()
        event.clear()
    clock.set_sim_time(rostime.Time(6))
    assert not event.is_set()


@pytest.mark.usefixtures("sim_time")
def test_a_waiting_thread_wakes_at_the_tick() -> None:
    event = threading.Event()
    woke: list[bool] = []
    with clock.woken_at_change(event):
        waiter = threading.Thread(target=lambda: woke.append(event.wait(30)))
        waiter.start()
        clock.set_sim_time(rostime.Time(7))
        waiter.join(30)
    assert woke == [True] and clock.is_sim_time()
