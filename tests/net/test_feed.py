"""ChildFeed: the newest value written to a child's stdin, offers that never block, the child's
own exit reported, and close() ending the child (by EOF, or by its PID when it reads no more)."""

from __future__ import annotations

import sys
import threading
import time
from pathlib import Path

from kame.net.feed import ChildFeed

# Reads lines and prints each one back, then 'eof' at the end of its input.
ECHO = "import sys\nfor line in sys.stdin:\n    print('got', line.strip(), flush=True)\nprint('eof', flush=True)"


def test_the_newest_value_reaches_the_child_and_close_ends_it_quietly(tmp_path: Path) -> None:
    out = tmp_path / "out.txt"
    exits: list[int] = []
    feed: ChildFeed[int] = ChildFeed([sys.executable, "-c", f"import sys; sys.stdout = open({str(out)!r}, 'w')\n"
                                      + ECHO], lambda v: f"{v}\n".encode(), exits.append)
    for value in range(100):
        feed.offer(value)
    deadline = time.monotonic() + 10
    out.touch()
    while "got 99" not in out.read_text():  # values in between may be skipped, never the newest
        assert time.monotonic() < deadline, out.read_text()
        time.sleep(0.02)
    feed.close()
    said = out.read_text().split()
    assert said[-1] == "eof"  # our EOF ended it
    seen = [int(word) for word in said if word.isdigit()]
    assert seen == sorted(seen)  # never an old value after a newer one
    assert exits == []  # we closed it: nothing to report


def test_the_child_exiting_by_itself_is_reported_with_its_status() -> None:
    ended = threading.Event()
    exits: list[int] = []

    def on_exit(status: int) -> None:
        exits.append(status)
        ended.set()

    feed: ChildFeed[bytes] = ChildFeed([sys.executable, "-c", "import sys; sys.stdin.readline(); sys.exit(5)"],
                                       bytes, on_exit)
    feed.offer(b"go\n")
    assert ended.wait(10)
    assert exits == [5]
    feed.offer(b"after\n")  # to a child that is gone: nothing happens
    feed.close()
    assert exits == [5]


def test_offers_never_block_and_a_child_that_reads_no_more_is_killed_on_close() -> None:
    exits: list[int] = []
    feed: ChildFeed[bytes] = ChildFeed([sys.executable, "-c", "import time; time.sleep(120)"], bytes, exits.append)
    chunk = b"x" * (1 << 20)
    for _ in range(50):  # 50 MB to a child that never reads: the pipe fills, the writer blocks, offer does not
        feed.offer(chunk)
    feed.close(timeout=1.0)
    assert exits == []
