"""tf listeners on a live graph, kame's against Debian's tf2_ros (Python over tf2's C++ core).

    .venv/bin/python bench/tf_listener_bench.py [--frames 20] [--rate 1000] [--seconds 10] [--wakeups 100]

Listener CPU: a kame master, one publisher sending /tf at `rate` Hz, each message the
`frames` transforms of a chain (as robot_state_publisher sends them), and two listeners
taking it at the same time: kame's tf2_ros.TransformListener in this interpreter, Debian's
under /usr/bin/python3, each in its own process. Each listener's CPU seconds per wall second
over `seconds` (from /proc), and how far behind the newest transform it was, asked once a
second (median and worst; a listener that did not keep up would fall further behind).

Wake-up latency: in one process per side, a thread waits in lookup_transform(time, timeout)
for a transform that is not there yet; another stores it with set_transform (what the
listener does when it arrives) after a random 10-60 ms; the time from that call to the waiter
returning. Table to stdout; every figure comes from this one run.
"""

from __future__ import annotations

import argparse
import json
import os
import random
import shutil
import statistics
import subprocess
import sys
import tempfile
import textwrap
import time
import xmlrpc.client
from pathlib import Path
from typing import Any

from bench_procs import cpu_seconds

SYSTEM_PYTHON = "/usr/bin/python3"

PUBLISHER = """
    import sys, threading, time, rospy, tf2_ros
    from geometry_msgs.msg import TransformStamped
    frames, rate = int(sys.argv[1]), float(sys.argv[2])
    rospy.init_node('tf_publisher')
    sent = [0]
    def report():
        for _ in sys.stdin:
            print(sent[0], flush=True)
    threading.Thread(target=report, daemon=True).start()
    broadcaster = tf2_ros.TransformBroadcaster()
    chain = []
    for index in range(frames):
        t = TransformStamped()
        t.header.frame_id, t.child_frame_id = f'f{index}', f'f{index + 1}'
        t.transform.translation.x = 1.0
        t.transform.rotation.w = 1.0
        chain.append(t)
    due = time.monotonic()
    while not rospy.is_shutdown():
        now = rospy.Time.now()
        for t in chain:
            t.header.stamp = now
        broadcaster.sendTransform(chain)
        sent[0] += 1
        due += 1.0 / rate
        delay = due - time.monotonic()
        if delay > 0:
            time.sleep(delay)
"""

LISTENER = """
    import sys, rospy, tf2_ros
    rospy.init_node('tf_listener', anonymous=True)
    buffer = tf2_ros.Buffer()
    listener = tf2_ros.TransformListener(buffer)
    tip = f'f{sys.argv[1]}'
    buffer.lookup_transform('f0', tip, rospy.Time(0), rospy.Duration(60))
    print('ready', flush=True)
    for _ in sys.stdin:
        newest = buffer.lookup_transform('f0', tip, rospy.Time(0)).header.stamp
        print((rospy.Time.now() - newest).to_sec(), flush=True)
"""


def wakeups(count: int) -> dict[str, float]:
    """Wake-up latencies (ms) of a lookup waiting for a transform stored by another thread."""
    import threading

    import rospy
    import tf2_ros
    from geometry_msgs.msg import TransformStamped

    if not rospy.core.is_initialized():  # Debian's waiting lookup reads rospy's clock: the wall clock here
        rospy.rostime.set_rostime_initialized(True)
    buffer = tf2_ros.Buffer(debug=False)
    delays = random.Random(1)
    latencies = []
    for index in range(count):
        stamp = rospy.Time(1000 + index)
        transform = TransformStamped()
        transform.header.frame_id, transform.child_frame_id, transform.header.stamp = "a", "b", stamp
        transform.transform.rotation.w = 1.0
        waiting, returned = threading.Event(), [0.0]

        def wait(stamp: Any = stamp, returned: list[float] = returned, waiting: threading.Event = waiting) -> None:
            waiting.set()
            buffer.lookup_transform("a", "b", stamp, rospy.Duration(5))
            returned[0] = time.perf_counter()

        waiter = threading.Thread(target=wait)
        waiter.start()
        waiting.wait()
        time.sleep(delays.uniform(0.01, 0.06))  # the waiter is inside its wait by now, at a random phase
        arrived = time.perf_counter()
        buffer.set_transform(transform, "/bench")
        waiter.join()
        latencies.append((returned[0] - arrived) * 1000)
    latencies.sort()
    return {"wake-up p50 ms": statistics.median(latencies), "wake-up p90 ms": latencies[int(0.9 * len(latencies))],
            "wake-up max ms": latencies[-1]}


def start(python: str, code: str, env: dict[str, str], *args: str) -> subprocess.Popen[str]:
    return subprocess.Popen([python, "-c", textwrap.dedent(code), *args], env=env, stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)


def stop(proc: subprocess.Popen[str]) -> None:
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def how_far_behind(listener: subprocess.Popen[str]) -> float:
    """Seconds between now and the newest transform the listener holds."""
    assert listener.stdin is not None and listener.stdout is not None
    listener.stdin.write("behind\n")
    listener.stdin.flush()
    return float(listener.stdout.readline())


def messages_sent(publisher: subprocess.Popen[str]) -> int:
    assert publisher.stdin is not None and publisher.stdout is not None
    publisher.stdin.write("count\n")
    publisher.stdin.flush()
    return int(publisher.stdout.readline())


def listener_cpu(frames: int, rate: float, seconds: float) -> dict[str, dict[str, float]]:
    home = Path(tempfile.mkdtemp(prefix="tf_listener_bench_"))
    import socket
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    uri = f"http://127.0.0.1:{port}/"
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_") and k != "PYTHONPATH"}
    env.update(ROS_HOME=str(home), ROS_LOG_DIR=str(home / "log"), ROS_HOSTNAME="127.0.0.1", ROS_MASTER_URI=uri,
               PYTHONUNBUFFERED="1")
    procs = [subprocess.Popen([sys.executable, "-m", "kame.cli.rosmaster", "--core", "-p", str(port)], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, text=True)]
    try:
        for _ in range(200):  # the master's port opens within a second or two
            try:
                xmlrpc.client.ServerProxy(uri).getPid("/bench")
                break
            except OSError:
                time.sleep(0.05)
        publisher = start(sys.executable, PUBLISHER, env, str(frames), str(rate))
        procs.append(publisher)
        listeners = {"kame": start(sys.executable, LISTENER, env, str(frames)),
                     "tf2_ros": start(SYSTEM_PYTHON, LISTENER, env, str(frames))}
        procs.extend(listeners.values())
        for name, proc in listeners.items():
            assert proc.stdout is not None
            if proc.stdout.readline().strip() != "ready":
                raise RuntimeError(f"the {name} listener did not get the chain")
        time.sleep(2.0)  # let both settle into the stream before measuring
        sent_before = messages_sent(publisher)
        before = {name: cpu_seconds(proc.pid) for name, proc in listeners.items()}
        started = time.monotonic()
        behind: dict[str, list[float]] = {name: [] for name in listeners}
        while time.monotonic() - started < seconds:
            time.sleep(min(1.0, max(0.0, seconds - (time.monotonic() - started))))
            for name, proc in listeners.items():
                behind[name].append(how_far_behind(proc))
        wall = time.monotonic() - started
        after = {name: cpu_seconds(proc.pid) for name, proc in listeners.items()}
        sent_rate = (messages_sent(publisher) - sent_before) / wall
        figures: dict[str, dict[str, float]] = {"publisher": {"messages sent per s": sent_rate}}
        for name in listeners:
            figures[name] = {"listener CPU s per s": (after[name] - before[name]) / wall,
                             "behind, median ms": statistics.median(behind[name]) * 1000,
                             "behind, worst ms": max(behind[name]) * 1000}
        return figures
    finally:
        for proc in reversed(procs):
            stop(proc)
        shutil.rmtree(home, ignore_errors=True)


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--frames", type=int, default=20)
    parser.add_argument("--rate", type=float, default=1000.0)
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--wakeups", type=int, default=100)
    parser.add_argument("--peer-wakeups", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.peer_wakeups:
        json.dump(wakeups(args.peer_wakeups), sys.stdout)
        return 0
    with open("/proc/loadavg") as loadavg:
        load_before = " ".join(loadavg.read().split()[:3])
    cpu = listener_cpu(args.frames, args.rate, args.seconds)
    woken = {}
    for name, python in (("kame", sys.executable), ("tf2_ros", SYSTEM_PYTHON)):
        done = subprocess.run([python, __file__, "--peer-wakeups", str(args.wakeups)], capture_output=True,
                              text=True, check=True, timeout=600)
        woken[name] = json.loads(done.stdout)
    with open("/proc/loadavg") as loadavg:
        load_after = " ".join(loadavg.read().split()[:3])
    print(f"/tf at {args.rate:g} Hz ({cpu['publisher']['messages sent per s']:.0f} messages/s sent), "
          f"{args.frames} transforms a message, {args.seconds:g} s measured; "
          f"{args.wakeups} wake-ups; load average {load_before} before, {load_after} after\n")
    print(f"| {'metric':<28} | {'tf2_ros (Debian)':>16} | {'kame':>10} |")
    print(f"| {'-' * 28} | {'-' * 16}:| {'-' * 10}:|")
    for metric in (*cpu["kame"], *woken["kame"]):
        theirs = cpu["tf2_ros"].get(metric, woken["tf2_ros"].get(metric, 0.0))
        ours = cpu["kame"].get(metric, woken["kame"].get(metric, 0.0))
        print(f"| {metric:<28} | {theirs:>16.3f} | {ours:>10.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
