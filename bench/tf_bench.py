"""tf2 lookups per second: kame's buffer core against Debian's tf2 (tf2_py, C++ underneath).

    .venv/bin/python bench/tf_bench.py [--links 10] [--stamps 100] [--lookups 20000]

The same script runs twice: in this interpreter on kame.tf, and under /usr/bin/python3 on
Debian's tf2_py (--peer). A chain of `links` frames, each with `stamps` transforms 10 ms apart,
then lookups from the chain's tip to its root at times between stamps (interpolating every
link) and at time 0 (latest). Table to stdout.
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


def run_kame(links: int, stamps: int, lookups: int) -> dict[str, float]:
    from kame.tf.buffer_core import BufferCore, Transform

    core = BufferCore()
    started = time.perf_counter()
    for link in range(links):
        for index in range(stamps):
            angle = 0.01 * index
            core.set_transform(Transform(f"f{link}", f"f{link + 1}", (1 + index) * 10_000_000, (1.0, 0.0, 0.0),
                                         (0.0, 0.0, math.sin(angle / 2), math.cos(angle / 2))), "/bench")
    inserted = time.perf_counter() - started
    tip = f"f{links}"
    started = time.perf_counter()
    for index in range(lookups):
        core.lookup_transform("f0", tip, (1 + index % (stamps - 1)) * 10_000_000 + 5_000_000)
    interpolated = time.perf_counter() - started
    started = time.perf_counter()
    for _ in range(lookups):
        core.lookup_transform("f0", tip, 0)
    latest = time.perf_counter() - started
    return {"inserts/s": links * stamps / inserted, "lookups/s (interpolated)": lookups / interpolated,
            "lookups/s (latest)": lookups / latest}


def run_debian(links: int, stamps: int, lookups: int) -> dict[str, float]:
    import rospy
    import tf2_py
    from geometry_msgs.msg import TransformStamped

    core = tf2_py.BufferCore(rospy.Duration(10))
    started = time.perf_counter()
    for link in range(links):
        for index in range(stamps):
            angle = 0.01 * index
            t = TransformStamped()
            t.header.frame_id, t.child_frame_id = f"f{link}", f"f{link + 1}"
            t.header.stamp = rospy.Time(0, (1 + index) * 10_000_000)
            t.transform.translation.x = 1.0
            t.transform.rotation.z, t.transform.rotation.w = math.sin(angle / 2), math.cos(angle / 2)
            core.set_transform(t, "/bench")
    inserted = time.perf_counter() - started
    tip = f"f{links}"
    times = [rospy.Time(0, (1 + index % (stamps - 1)) * 10_000_000 + 5_000_000) for index in range(stamps)]
    started = time.perf_counter()
    for index in range(lookups):
        core.lookup_transform_core("f0", tip, times[index % (stamps - 1)])
    interpolated = time.perf_counter() - started
    zero = rospy.Time(0)
    started = time.perf_counter()
    for _ in range(lookups):
        core.lookup_transform_core("f0", tip, zero)
    latest = time.perf_counter() - started
    return {"inserts/s": links * stamps / inserted, "lookups/s (interpolated)": lookups / interpolated,
            "lookups/s (latest)": lookups / latest}


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--links", type=int, default=10)
    parser.add_argument("--stamps", type=int, default=100)
    parser.add_argument("--lookups", type=int, default=20000)
    parser.add_argument("--peer", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.peer:
        json.dump(run_debian(args.links, args.stamps, args.lookups), sys.stdout)
        return 0
    ours = run_kame(args.links, args.stamps, args.lookups)
    theirs: dict[str, Any] = {}
    try:
        done = subprocess.run([SYSTEM_PYTHON, __file__, "--peer", "--links", str(args.links), "--stamps",
                               str(args.stamps), "--lookups", str(args.lookups)], capture_output=True, text=True,
                              check=True, timeout=600)
        theirs = json.loads(done.stdout)
    except (OSError, subprocess.SubprocessError, ValueError) as exc:
        print(f"Debian's tf2_py did not run: {exc}", file=sys.stderr)
    print(f"chain of {args.links} links, {args.stamps} stamps each, {args.lookups} lookups tip -> root\n")
    print(f"| {'metric':<26} | {'tf2 (C++, tf2_py)':>18} | {'kame':>12} | {'kame / tf2':>10} |")
    print(f"| {'-' * 26} | {'-' * 18}:| {'-' * 12}:| {'-' * 10}:|")
    for metric, value in ours.items():
        real = theirs.get(metric)
        ratio = f"{value / real:.2f}" if real else "n/a"
        real_text = f"{real:,.0f}" if real else "n/a"
        print(f"| {metric:<26} | {real_text:>18} | {value:>12,.0f} | {ratio:>10} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
