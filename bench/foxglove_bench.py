"""foxglove_bridge under a 1080p camera (issue 36): a kame publisher sends a 1920x1080 rgb8
sensor_msgs/Image (6.2 MB) at --rate Hz; kame's foxglove_bridge forwards it to Foxglove's own
client (@foxglove/ws-protocol in Node, tests/web/foxglove_client.js). Printed: the frames per
second the client received, the bridge's CPU (user + system from /proc, in cores) over the same
window, the client's CPU and the load average. Targets: >= 25 fps, <= 1 core for the bridge.

The same run with a second client that subscribes and never reads (`--stuck`) shows what a slow
client costs: the bridge's VmRSS before and after, with send_buffer_limit (10 MB) as the bound.
Bounded: --seconds of measuring (default 10) after a warm-up. Needs tests/web/node_modules
(bash scripts/install-web-peers.sh). Run: .venv/bin/python bench/foxglove_bench.py
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import socket
import subprocess
import sys
import tempfile
import time
import xmlrpc.client
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
WEB = REPO / "tests" / "web"
PYTHON = sys.executable

PUBLISHER = """
import sys, rospy
from sensor_msgs.msg import Image
rospy.init_node("camera")
pub = rospy.Publisher("/camera/image_raw", Image, queue_size=2)
w, h = 1920, 1080
data = bytes(range(256)) * (w * h * 3 // 256)
msg = Image(height=h, width=w, encoding="rgb8", step=w * 3, data=data)
rate = rospy.Rate(float(sys.argv[1]))
print("ready", flush=True)
while not rospy.is_shutdown():
    msg.header.stamp = rospy.Time.now()
    pub.publish(msg)
    try:
        rate.sleep()
    except rospy.ROSInterruptException:
        break
"""

STUCK = """
import json, sys, time
from websockets.sync.client import connect
with connect(sys.argv[1], subprotocols=["foxglove.websocket.v1"], max_size=None, max_queue=1) as ws:
    while True:
        message = json.loads(ws.recv())
        if message["op"] == "advertise":
            ids = [c["id"] for c in message["channels"] if c["topic"] == "/camera/image_raw"]
            if ids:
                ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": ids[0]}]}))
                break
    print("stuck", flush=True)
    try:
        sys.stdin.read()  # never reads the socket again; ends when the bench closes our stdin
    except KeyboardInterrupt:
        pass
"""


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def cpu_seconds(pid: int) -> float:
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def rss_mb(pid: int) -> float:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return 0.0


def stop(proc: subprocess.Popen[str]) -> None:
    if proc.poll() is None:
        proc.send_signal(signal.SIGINT)
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def wait_line(proc: subprocess.Popen[str], text: str) -> None:
    assert proc.stdout is not None
    for line in proc.stdout:
        if text in line:
            return
    raise RuntimeError(f"{proc.args!r} ended before printing {text!r}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rate", type=float, default=30.0)
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--stuck", action="store_true", help="add a client that subscribes and never reads")
    parser.add_argument("--send-buffer-limit", type=int, default=10_000_000, help="the bridge's, in bytes")
    args = parser.parse_args()
    home = Path(tempfile.mkdtemp(prefix="foxglove-bench-"))
    uri = f"http://127.0.0.1:{free_port()}/"
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_") and k != "PYTHONPATH"}
    env.update(ROS_MASTER_URI=uri, ROS_HOME=str(home), ROS_HOSTNAME="127.0.0.1", PYTHONUNBUFFERED="1")
    port = free_port()
    procs: list[subprocess.Popen[str]] = []

    def start(argv: list[str], ready: str | None = None, stdin: int | None = None) -> subprocess.Popen[str]:
        proc = subprocess.Popen(argv, env=env, cwd=home, stdout=subprocess.PIPE, stdin=stdin, text=True)
        procs.append(proc)
        if ready is not None:
            wait_line(proc, ready)
        return proc

    try:
        start([PYTHON, "-m", "kame.cli.rosmaster", "--core", "-p", uri.rsplit(":", 1)[1][:-1]])
        deadline = time.monotonic() + 20
        while True:
            try:
                xmlrpc.client.ServerProxy(uri).getPid("/bench")
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.1)
        start([PYTHON, "-c", PUBLISHER, str(args.rate)], "ready")
        bridge = start([PYTHON, str(REPO / "src/kame/lib/foxglove_bridge/foxglove_bridge"), f"_port:={port}",
                        "_max_update_ms:=500", f"_send_buffer_limit:={args.send_buffer_limit}"], "serving ws://")
        stuck = None
        rss_before = rss_mb(bridge.pid)
        if args.stuck:
            stuck = start([PYTHON, "-c", STUCK, f"ws://127.0.0.1:{port}"], "stuck", stdin=subprocess.PIPE)
        plan = json.dumps({"url": f"ws://127.0.0.1:{port}",
                           "steps": [{"rate": "/camera/image_raw", "seconds": 2},
                                     {"rate": "/camera/image_raw", "seconds": args.seconds}]})
        client = subprocess.Popen(["node", str(WEB / "foxglove_client.js"), plan], cwd=WEB, stdout=subprocess.PIPE,
                                  text=True)
        assert client.stdout is not None
        lines = iter(client.stdout)
        next(lines)  # serverInfo
        next(lines)  # the warm-up
        cpu_start, wall_start = cpu_seconds(bridge.pid), time.monotonic()
        measured = json.loads(next(lines))
        bridge_cores = (cpu_seconds(bridge.pid) - cpu_start) / (time.monotonic() - wall_start)
        client.wait(30)
        rss_after = rss_mb(bridge.pid)
        dropped = "?"
        assert bridge.stdout is not None
        for line in bridge.stdout:  # the bridge says what it dropped for the client when it leaves
            if "disconnected (" in line:
                dropped = line.split("disconnected (", 1)[1].split()[0]
                break
        if stuck is not None and stuck.stdin is not None:
            stuck.stdin.close()
        print(f"foxglove_bridge, 1080p rgb8 at {args.rate:.0f} Hz, {args.seconds:.0f} s, send buffer limit "
              f"{args.send_buffer_limit / 1e6:.0f} MB, load average {os.getloadavg()[0]:.1f}")
        throughput = measured["bytes"] / measured["seconds"] / 1e6
        print(f"  client received   {measured['fps']:6.1f} fps  ({throughput:.0f} MB/s; the bridge dropped {dropped} "
              "at its send buffer limit, warm-up included)")
        print(f"  bridge CPU        {bridge_cores:6.2f} cores")
        print(f"  client CPU        {measured['clientCpu']:6.2f} cores (Node, ws-protocol)")
        print(f"  bridge VmRSS      {rss_before:6.0f} MB before, {rss_after:.0f} MB after"
              + (" (with a client that never reads)" if stuck is not None else ""))
    finally:
        for proc in reversed(procs):
            stop(proc)
    return 0


if __name__ == "__main__":
    sys.exit(main())
