"""A slow subscriber beside a fast one (issue 15): the publisher's memory and the fast
subscriber's rate, with and without a subscriber that takes 1 s per message.

    .venv/bin/python bench/slow_subscriber.py [--seconds 20] [--rate 1000] [--size 1000]

A kame master; a rospy-API publisher of std_msgs/String (--size bytes) at --rate Hz with
queue_size 10; a fast subscriber counting what arrives; in the second run also a slow one
(queue_size 1, sleeps 1 s in its callback). Printed per run: the publisher's resident memory
(VmRSS) 2 s in and at the end, and the fast subscriber's messages per second. Flat memory and
an unchanged rate are the goal: one slow subscriber must cost the others nothing.
"""

from __future__ import annotations

import argparse
import os
import socket
import subprocess
import sys
import textwrap
import time
from pathlib import Path

from bench_procs import free_port

PUBLISHER = """
import os, sys, time, rospy
from std_msgs.msg import String
rate, size, seconds, wanted = float(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])
rospy.init_node('talker')
pub = rospy.Publisher('/flood', String, queue_size=10)
while pub.get_num_connections() < wanted and not rospy.is_shutdown():
    rospy.sleep(0.01)
def rss():
    with open(f'/proc/{os.getpid()}/status') as f:
        return next(int(line.split()[1]) for line in f if line.startswith('VmRSS'))
text, period, start, early = 'x' * size, 1.0 / rate, time.monotonic(), None
n = 0
while time.monotonic() - start < seconds:
    pub.publish(text)
    n += 1
    if early is None and time.monotonic() - start >= 2.0:
        early = rss()
    delay = start + n * period - time.monotonic()
    if delay > 0:
        time.sleep(delay)
print('published', n, 'rss_kb', early, rss(), flush=True)
"""

SUBSCRIBER = """
import sys, time, rospy
from std_msgs.msg import String
slow = sys.argv[1] == 'slow'
got = []
def callback(msg):
    got.append(time.monotonic())
    if slow:
        time.sleep(1.0)
rospy.init_node('slow' if slow else 'fast')
rospy.Subscriber('/flood', String, callback, queue_size=1 if slow else 10)
print('ready', flush=True)
rospy.spin()
span = got[-1] - got[0] if len(got) > 1 else 0.0
print('received', len(got), 'rate', round((len(got) - 1) / span) if span else 0, flush=True)
"""


def python(code: str, *args: str, env: dict[str, str]) -> subprocess.Popen[str]:
    return subprocess.Popen([sys.executable, "-c", textwrap.dedent(code), *args], env=env, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)


def run(with_slow: bool, seconds: float, rate: float, size: int, env: dict[str, str]) -> str:
    subscribers = [python(SUBSCRIBER, "fast", env=env)]
    if with_slow:
        subscribers.append(python(SUBSCRIBER, "slow", env=env))
    for sub in subscribers:
        assert sub.stdout is not None and sub.stdout.readline().strip() == "ready"
    publisher = python(PUBLISHER, str(rate), str(size), str(seconds), str(len(subscribers)), env=env)
    published, _ = publisher.communicate(timeout=seconds + 60)
    time.sleep(0.5)  # what is still on its way to the fast subscriber
    results = []
    for sub in subscribers:
        sub.send_signal(2)
        out, _ = sub.communicate(timeout=30)
        results.append(out.strip().splitlines()[-1])
    words = published.split()
    return (f"publisher RSS {words[3]} kB at 2 s, {words[4]} kB at the end; fast subscriber: {results[0]}"
            + (f"; slow subscriber: {results[1]}" if with_slow else ""))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--rate", type=float, default=1000.0)
    parser.add_argument("--size", type=int, default=1000)
    options = parser.parse_args()
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = dict(os.environ, ROS_MASTER_URI=uri, ROS_HOME=str(Path("/tmp") / f"kame-slow-bench-{os.getpid()}"))
    master = subprocess.Popen([sys.executable, "-m", "kame.cli.rosmaster", "--core", "-p", str(port)], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 20
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.05)
        print(f"{options.rate:.0f} Hz of {options.size}-byte messages for {options.seconds:.0f} s, "
              f"load average {os.getloadavg()[0]:.1f}")
        for with_slow in (False, True):
            label = "with a slow subscriber   " if with_slow else "without a slow subscriber"
            print(label, run(with_slow, options.seconds, options.rate, options.size, env), flush=True)
    finally:
        master.terminate()
        master.wait(10)


if __name__ == "__main__":
    main()
