"""Intra-process delivery (issue 21): a rospy node hearing its own topic, objects vs the wire.

Usage: .venv/bin/python bench/intraprocess_bench.py [--seconds 3]
Runs itself once per mode in a child process (KAME_INTRAPROCESS=1, then 0 with KAME_SHM=0 and
with KAME_SHM=1) with a kame master of its own, publishing String and 1080p Image messages to a
Subscriber in the same node with at most 3 unheard; prints messages/s and the ratio to the wire.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import threading
import time

MODES = {"intraprocess": {"KAME_INTRAPROCESS": "1"},
         "TCPROS": {"KAME_INTRAPROCESS": "0", "KAME_SHM": "0"},
         "shared memory": {"KAME_INTRAPROCESS": "0", "KAME_SHM": "1"}}


def child(seconds: float) -> None:
    import rospy
    from sensor_msgs.msg import Image
    from std_msgs.msg import String

    rospy.init_node("intraprocess_bench")
    rates = {}
    for name, cls, make in (("String", String, lambda: String(data="hello")),
                            ("Image 1080p", Image, lambda: Image(height=1080, width=1920, encoding="rgb8",
                                                                 step=5760, data=bytes(1920 * 1080 * 3)))):
        heard, cv = [0], threading.Condition()

        def on_message(msg: object, heard: list[int] = heard, cv: threading.Condition = cv) -> None:
            with cv:
                heard[0] += 1
                cv.notify()

        topic = "/bench_" + cls.__name__.lower()
        sub = rospy.Subscriber(topic, cls, on_message, queue_size=10)
        pub = rospy.Publisher(topic, cls, queue_size=10)
        while pub.get_num_connections() < 1:
            time.sleep(0.01)
        sent, end = 0, time.monotonic() + seconds
        started = time.monotonic()
        while time.monotonic() < end:
            with cv:
                cv.wait_for(lambda: sent - heard[0] < 3, timeout=1.0)  # noqa: B023 (called now)
            pub.publish(make())
            sent += 1
        with cv:
            cv.wait_for(lambda: heard[0] >= sent, timeout=5.0)  # noqa: B023 (called now)
        rates[name] = heard[0] / (time.monotonic() - started)
        pub.unregister()
        sub.unregister()
    print("RESULT " + json.dumps(rates), flush=True)
    rospy.signal_shutdown("done")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=3.0)
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    options = parser.parse_args()
    if options.child:
        child(options.seconds)
        return
    import socket

    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    uri = f"http://127.0.0.1:{port}/"
    home = tempfile.mkdtemp(prefix="intraprocess_bench.")
    env = {**os.environ, "ROS_MASTER_URI": uri, "ROS_HOSTNAME": "127.0.0.1", "ROS_HOME": home,
           "ROS_LOG_DIR": home}
    master = subprocess.Popen([sys.executable, "-m", "kame.cli.rosmaster", "--core", "-p", str(port)], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        time.sleep(1.5)
        results = {}
        for mode, extra in MODES.items():
            out = subprocess.run([sys.executable, __file__, "--child", "--seconds", str(options.seconds)],
                                 env={**env, **extra}, capture_output=True, text=True, timeout=120).stdout
            line = next(line for line in out.splitlines() if line.startswith("RESULT "))
            results[mode] = json.loads(line[len("RESULT "):])
    finally:
        master.terminate()
        master.wait()
    with open("/proc/loadavg") as f:
        load = " ".join(f.read().split()[:3])
    print(f"messages/s heard by a subscriber in the publishing node, <= 3 unheard (load {load})")
    for message in results["intraprocess"]:
        wire = results["TCPROS"][message]
        print(f"  {message:12s} " + "  ".join(f"{mode} {r[message]:,.0f}" for mode, r in results.items())
              + f"  (intraprocess/TCPROS {results['intraprocess'][message] / wire:.2f}x)")


if __name__ == "__main__":
    main()
