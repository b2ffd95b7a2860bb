"""SupervisedProcess: stdout to a file, respawn after an unasked exit, stop by PID with escalation."""

from __future__ import annotations

import asyncio
import itertools
import os
import signal
import sys
import time
from pathlib import Path

from kame.net.process import SupervisedProcess

# The default SIGINT handler set explicitly: a shell that runs the tests in the background
# (`cmd &` without job control) hands every child SIGINT ignored, and Python keeps it so.
SLEEPER = ("import signal, time\nsignal.signal(signal.SIGINT, signal.default_int_handler)\n"
           "print('up', flush=True)\ntime.sleep(60)\n")
STUBBORN = ("import signal, time\nsignal.signal(signal.SIGINT, signal.SIG_IGN)\nprint('up', flush=True)\n"
            "time.sleep(60)\n")


async def wait_for(predicate, timeout: float = 10.0) -> None:  # type: ignore[no-untyped-def]
    deadline = time.monotonic() + timeout
    while not predicate():
        assert time.monotonic() < deadline, "condition not reached"
        await asyncio.sleep(0.02)


def test_respawn_and_stop(tmp_path: Path) -> None:
    out = tmp_path / "logs" / "child-stdout.log"
    starts: list[tuple[int, bool]] = []
    exits: list[tuple[int, int]] = []

    async def scenario() -> None:
        child = SupervisedProcess("child", [sys.executable, "-c", SLEEPER], stdout=out, respawn=True,
                                  on_start=lambda pid, again: starts.append((pid, again)),
                                  on_exit=lambda pid, code: exits.append((pid, code)))
        first = await child.start()
        try:
            await wait_for(lambda: out.exists() and out.read_text().count("up") == 1)
            os.kill(first, signal.SIGKILL)
            await wait_for(lambda: len(starts) == 2)
            assert exits == [(first, -signal.SIGKILL)]
            assert child.pid == starts[1][0] != first
            await wait_for(lambda: out.read_text().count("up") == 2)  # appended, not truncated
        finally:
            code = await child.stop(timeout=5.0)
        assert code == -signal.SIGINT  # Python re-raises an uncaught KeyboardInterrupt as SIGINT
        assert len(starts) == 2 and exits == [(first, -signal.SIGKILL)]  # the stop was not a death

    asyncio.run(scenario())
    assert [again for _, again in starts] == [False, True]


def test_stop_escalates_to_sigkill(tmp_path: Path) -> None:
    out = tmp_path / "stdout.log"

    async def scenario() -> float:
        child = SupervisedProcess("stubborn", [sys.executable, "-c", STUBBORN], stdout=out, respawn=True)
        await child.start()
        await wait_for(lambda: out.exists() and "up" in out.read_text())
        t0 = time.monotonic()
        assert await child.stop(timeout=0.3) == -signal.SIGKILL
        return time.monotonic() - t0

    assert asyncio.run(scenario()) < 2.0


def test_no_respawn_without_asking(tmp_path: Path) -> None:
    starts: list[int] = []

    async def scenario() -> None:
        child = SupervisedProcess("once", [sys.executable, "-c", "pass"], on_start=lambda pid, _: starts.append(pid))
        await child.start()
        await asyncio.sleep(0.5)
        assert await child.stop() == 0

    asyncio.run(scenario())
    assert len(starts) == 1


def test_respawn_backoff_doubles_for_young_deaths_and_resets_after_a_long_life() -> None:
    from kame.net.backoff import RespawnBackoff

    backoff = RespawnBackoff()
    delays = [backoff.delay(0.1, 0.0) for _ in range(10)]
    assert delays == [(0.0, False), (0.5, True), (1.0, True), (2.0, True), (4.0, True), (8.0, True),
                      (16.0, True), (30.0, True), (30.0, False), (30.0, False)]  # each step said once
    assert backoff.delay(60.0, 0.0) == (0.0, False)  # a long life: afresh
    assert backoff.delay(0.1, 0.0) == (0.0, False) and backoff.delay(0.1, 0.0) == (0.5, True)
    slow = RespawnBackoff()
    assert [slow.delay(0.1, 3.0) for _ in range(5)] == [(3.0, False), (3.0, False), (3.0, False), (3.0, False),
                                                        (4.0, True)]  # a longer respawn_delay wins


def test_a_child_that_crashes_at_start_is_restarted_ever_more_slowly(tmp_path: Path) -> None:
    starts: list[float] = []

    async def scenario() -> None:
        child = SupervisedProcess("crashy", [sys.executable, "-c", "raise SystemExit(1)"], respawn=True,
                                  on_start=lambda pid, again: starts.append(time.monotonic()))
        await child.start()
        try:
            await wait_for(lambda: len(starts) == 4, timeout=30)
        finally:
            await child.stop()

    asyncio.run(scenario())
    gaps = [b - a for a, b in itertools.pairwise(starts)]
    assert gaps[1] >= 0.5 and gaps[2] >= 1.0  # it used to be restarted as fast as it died
