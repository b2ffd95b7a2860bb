"""tf_monitor: `tf_monitor` reports, every couple of seconds, each frame's publisher and the
delay between its stamps and their arrival, and each broadcaster's rate and delay;
`tf_monitor a b` adds the chain between the two frames and its net delay. The text is tf's
(numbers as C++ streams print them). Publishers are named by their callerid (Debian's prints
`unknown_publisher` there)."""

from __future__ import annotations

import sys
import threading
from collections import deque
from collections.abc import Sequence
from typing import Any

from kame.cli._tf import listening_buffer, start_node
from kame.tf import errors
from kame.tf.buffer_core import strip_slash
from kame.tf.messages import to_nsec

KEEP = 1000  # samples kept per frame and per broadcaster, as tf_monitor
ROUND = 0.1  # seconds: tf_monitor's loop
REPORT_ROUNDS = 20  # a report after every 21st round


def number(value: float) -> str:
    """A double as std::cout prints it by default (six significant digits)."""
    return f"{value:g}"


class Statistics:
    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.frame_authority: dict[str, str] = {}
        self.frame_delays: dict[str, deque[float]] = {}
        self.authority_delays: dict[str, deque[float]] = {}
        self.authority_arrivals: dict[str, deque[float]] = {}

    def record(self, msg: Any, authority: str, is_static: bool, now: float) -> None:
        if is_static:
            authority += "(static)"
        total = 0.0
        with self.lock:
            for transform in msg.transforms:
                child = transform.child_frame_id
                delay = 0.0 if is_static else now - to_nsec(transform.header.stamp) / 1e9
                total += delay
                self.frame_authority[child] = authority
                self.frame_delays.setdefault(child, deque(maxlen=KEEP)).append(delay)
            self.authority_delays.setdefault(authority, deque(maxlen=KEEP)).append(total / max(1, len(msg.transforms)))
            self.authority_arrivals.setdefault(authority, deque(maxlen=KEEP)).append(now)

    def report(self) -> str:
        with self.lock:
            lines = ["", "Frames:"]
            for frame in sorted(self.frame_delays):
                delays = self.frame_delays[frame]
                average, worst = sum(delays) / len(delays), max(0.0, *delays)
                lines.append(f"Frame: {frame} published by {self.frame_authority[frame]} "
                             f"Average Delay: {number(average)} Max Delay: {number(worst)}")
            lines += ["", "All Broadcasters:"]
            for authority in sorted(self.authority_delays):
                delays, arrivals = self.authority_delays[authority], self.authority_arrivals[authority]
                rate = len(arrivals) / max(0.00000001, arrivals[-1] - arrivals[0])
                lines.append(f"Node: {authority} {number(rate)} Hz, Average Delay: "
                             f"{number(sum(delays) / len(delays))} Max Delay: {number(max(0.0, *delays))}")
        return "\n".join(lines) + "\n"


def main(argv: Sequence[str] | None = None) -> int:
    tool, args = start_node(sys.argv[1:] if argv is None else argv, "tf_monitor")
    try:
        if len(args) not in (0, 2):
            print("usage: tf_monitor [source_frame target_frame]", flush=True)
            return 255
        if not tool.wait_for_master():
            return 0
        statistics = Statistics()
        buffer, _ = listening_buffer(
            tool, on_message=lambda msg, who, static: statistics.record(msg, who, static, tool.now_ns() / 1e9))
        chain: list[str] = []
        if args:
            source, target = strip_slash(args[0]), strip_slash(args[1])
            print(f"Waiting for transform chain to become available between {source} and {target} ", flush=True)
            while not buffer.can_transform(source, target, 0, 1.0):
                if tool.stop.is_set():
                    return 0
            chain = buffer.chain(target, source)
        average = maximum = 0.0
        rounds = 0
        while not tool.stop.wait(ROUND):
            if chain:  # the chain's delay is sampled each round, reported every REPORT_ROUNDS
                try:
                    stamp = buffer.lookup_transform(chain[0], chain[-1], 0).header.stamp
                    delay = (tool.now_ns() - to_nsec(stamp)) / 1e9
                    average = 0.01 * delay + 0.99 * average
                    maximum = max(maximum, delay)
                except errors.TransformException:
                    pass
            rounds += 1
            if rounds <= REPORT_ROUNDS:
                continue
            rounds = 0
            if chain:
                print(f"\n\n\nRESULTS: for {chain[0]} to {chain[-1]}\nChain is: {' -> '.join(chain)}\n"
                      f"Net delay     avg = {number(average)}: max = {number(maximum)}", flush=True)
            else:
                print("\n\n\nRESULTS: for all Frames", flush=True)
            print(statistics.report(), end="", flush=True)
        return 0
    finally:
        tool.node.shutdown("tf_monitor exiting")


if __name__ == "__main__":
    sys.exit(main())
