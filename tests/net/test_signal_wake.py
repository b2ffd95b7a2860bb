"""A main thread waiting on a SignalSafeEvent: a SIGINT that the kernel gives to another thread
still runs the handler at once, and the handler's event ends the wait (a plain Event.wait()
without timeout would sleep on: Python only flags the signal for the main thread)."""

from __future__ import annotations

import subprocess
import sys
import textwrap

from tests.support import REPO

PROGRAM = """
import signal, threading, time
from kame.net.signal_wake import SignalSafeEvent
stop = SignalSafeEvent()
signal.signal(signal.SIGINT, lambda signum, frame: stop.set())
main_task = '/proc/self/task/%d/stat' % threading.main_thread().native_id
def main_sleeps():
    with open(main_task) as stat:
        return stat.read().rsplit(')', 1)[1].split()[0] == 'S'
def interrupt_from_here():
    time.sleep(0.2)
    while not main_sleeps():
        time.sleep(0.01)  # the main thread's state has no event to wait on
    signal.pthread_kill(threading.get_ident(), signal.SIGINT)
threading.Thread(target=interrupt_from_here, name='interrupter').start()
print('woke:', stop.wait(), flush=True)
done = SignalSafeEvent()
threading.Timer(0.2, done.set).start()  # set from another thread: the main thread's wait ends too
print('set elsewhere:', done.wait(), flush=True)
print('timed out:', not SignalSafeEvent().wait(0.05), flush=True)
"""


def test_a_signal_caught_by_another_thread_ends_the_main_threads_wait() -> None:
    run = subprocess.run([sys.executable, "-c", textwrap.dedent(PROGRAM)], cwd=REPO, capture_output=True,
                         text=True, timeout=20)
    assert run.stdout.splitlines() == ["woke: True", "set elsewhere: True", "timed out: True"], run.stderr
