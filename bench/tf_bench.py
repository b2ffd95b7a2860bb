"""tf2 lookups per second: kame's buffer core against Debian's tf2 (tf2_py, C++ underneath).

    .venv/bin/python bench/tf_bench.py [--links 10] [--stamps 100] [--lookups 20000] [--rounds 3]

The same script runs twice: in this interpreter on kame.tf, and under /usr/bin/python3 on
Debian's tf2_py (--peer). A chain of `links` frames, each with `stamps` transforms 10 ms apart,
then lookups from the chain's tip to its root: at the times halfway between stamps, in turn
(interpolating every link; the same times come back, as when many points of one scan are
transformed), at a new time each lookup (the walk itself, nothing to remember), and at time 0
(latest). The core's lookups return its own transform type (kame: a tuple; tf2_py: a
message built in C++); the last rows go through tf2_ros.Buffer.lookup_transform, a
TransformStamped message out on both sides. Rates are per CPU second (the machine is shared); the two sides run in turn
`rounds` times and the best round of each counts. Table to stdout; every ratio comes from
this one run.
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import time
from typing import Any

SYSTEM_PYTHON = "/usr/bin/python3"


def lookup_times(stamps: int, lookups: int) -> tuple[list[int], list[int]]:
    """(times between stamps that come back in turn, a different time for every lookup), in ns."""
    halfway = [(1 + index % (stamps - 1)) * 10_000_000 + 5_000_000 for index in range(lookups)]
    return halfway, [stamp + index for index, stamp in enumerate(halfway)]


def run_kame(links: int, stamps: int, lookups: int) -> dict[str, float]:
    from kame.tf.buffer_core import BufferCore, Transform

    core = BufferCore()
    started = time.process_time()
    for link in range(links):
        for index in range(stamps):
            angle = 0.01 * index
            core.set_transform(Transform(f"f{link}", f"f{link + 1}", (1 + index) * 10_000_000, (1.0, 0.0, 0.0),
                                         (0.0, 0.0, math.sin(angle / 2), math.cos(angle / 2))), "/bench")
    inserted = time.process_time() - started
    tip = f"f{links}"
    halfway, every_time_new = lookup_times(stamps, lookups)
    figures = {"inserts/s": links * stamps / inserted}
    for metric, times in (("lookups/s (interpolated)", halfway), ("lookups/s (each time new)", every_time_new),
                          ("lookups/s (latest)", [0] * lookups)):
        started = time.process_time()
        for stamp in times:
            core.lookup_transform("f0", tip, stamp)
        figures[metric] = lookups / (time.process_time() - started)
    return figures


def run_buffer(links: int, stamps: int, lookups: int) -> dict[str, float]:
    """tf2_ros.Buffer, the API programs use: the same code on both sides (kame's facades or Debian's)."""
    import rospy
    import tf2_ros
    from geometry_msgs.msg import TransformStamped

    buffer = tf2_ros.Buffer(debug=False)
    for link in range(links):
        for index in range(stamps):
            angle = 0.01 * index
            t = TransformStamped()
            t.header.frame_id, t.child_frame_id = f"f{link}", f"f{link + 1}"
            t.header.stamp = rospy.Time(0, (1 + index) * 10_000_000)
            t.transform.translation.x = 1.0
            t.transform.rotation.z, t.transform.rotation.w = math.sin(angle / 2), math.cos(angle / 2)
            buffer.set_transform(t, "/bench")
    tip = f"f{links}"
    figures = {}
    for metric, stamps_ns in (("Buffer.lookup_transform/s (each time new)", lookup_times(stamps, lookups)[1]),
                              ("Buffer.lookup_transform/s (latest)", [0] * lookups)):
        times = [rospy.Time(0, stamp) for stamp in stamps_ns]
        started = time.process_time()
        for stamp in times:
            buffer.lookup_transform("f0", tip, stamp)
        figures[metric] = lookups / (time.process_time() - started)
    return figures


def run_debian(links: int, stamps: int, lookups: int) -> dict[str, float]:
    import rospy
    import tf2_py
    from geometry_msgs.msg import TransformStamped

    core = tf2_py.BufferCore(rospy.Duration(10))
    started = time.process_time()
    for link in range(links):
        for index in range(stamps):
            angle = 0.01 * index
            t = TransformStamped()
            t.header.frame_id, t.child_frame_id = f"f{link}", f"f{link + 1}"
            t.header.stamp = rospy.Time(0, (1 + index) * 10_000_000)
            t.transform.translation.x = 1.0
            t.transform.rotation.z, t.transform.rotation.w = math.sin(angle / 2), math.cos(angle / 2)
            core.set_transform(t, "/bench")
    inserted = time.process_time() - started
    tip = f"f{links}"
    halfway, every_time_new = lookup_times(stamps, lookups)
    figures = {"inserts/s": links * stamps / inserted}
    for metric, stamps_ns in (("lookups/s (interpolated)", halfway), ("lookups/s (each time new)", every_time_new),
                              ("lookups/s (latest)", [0] * lookups)):
        times = [rospy.Time(0, stamp) for stamp in stamps_ns]
        started = time.process_time()
        for stamp in times:
            core.lookup_transform_core("f0", tip, stamp)
        figures[metric] = lookups / (time.process_time() - started)
    return figures


def best(kept: dict[str, float], figures: dict[str, float]) -> None:
    for metric, value in figures.items():
        kept[metric] = max(kept.get(metric, 0.0), value)


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--links", type=int, default=10)
    parser.add_argument("--stamps", type=int, default=100)
    parser.add_argument("--lookups", type=int, default=20000)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--peer", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.peer:
        json.dump({**run_debian(args.links, args.stamps, args.lookups),
                   **run_buffer(args.links, args.stamps, args.lookups)}, sys.stdout)
        return 0
    ours: dict[str, float] = {}
    theirs: dict[str, Any] = {}
    for _ in range(args.rounds):
        best(ours, run_kame(args.links, args.stamps, args.lookups))
        best(ours, run_buffer(args.links, args.stamps, args.lookups))
        try:
            done = subprocess.run([SYSTEM_PYTHON, __file__, "--peer", "--links", str(args.links), "--stamps",
                                   str(args.stamps), "--lookups", str(args.lookups)], capture_output=True,
                                  text=True, check=True, timeout=600)
            best(theirs, json.loads(done.stdout))
        except (OSError, subprocess.SubprocessError, ValueError) as exc:
            print(f"Debian's tf2_py did not run: {exc}", file=sys.stderr)
    with open("/proc/loadavg") as loadavg:
        load = " ".join(loadavg.read().split()[:3])
    print(f"chain of {args.links} links, {args.stamps} stamps each, {args.lookups} lookups tip -> root, "
          f"best of {args.rounds} rounds per CPU second, load average {load}\n")
    print(f"| {'metric':<42} | {'tf2 (C++, tf2_py)':>18} | {'kame':>12} | {'kame / tf2':>10} |")
    print(f"| {'-' * 42} | {'-' * 18}:| {'-' * 12}:| {'-' * 10}:|")
    for metric, value in ours.items():
        real = theirs.get(metric)
        ratio = f"{value / real:.2f}" if real else "n/a"
        real_text = f"{real:,.0f}" if real else "n/a"
        print(f"| {metric:<42} | {real_text:>18} | {value:>12,.0f} | {ratio:>10} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
