"""kame's rosbridge (issue 36): publish-to-browser-client latency, and 10 clients at 1 kHz.

    .venv/bin/python bench/rosbridge_bench.py [--seconds 10] [--latency-rate 50] [--rate 1000] [--clients 10]

kame's master, `rosrun rosbridge_server rosbridge_websocket` (kame's) and a rospy-API publisher
(kame's rospy) of std_msgs/String carrying "N WALLTIME", stamped just before publish().
- Latency: --latency-rate Hz for --seconds to one roslibjs client in Node (what a browser page
  runs) through the bridge; beside it, as the comparison this machine allows (ROS has no bridge
  of its own: rosbridge_suite is not installed here), the same messages over TCPROS to a kame
  rospy subscriber and, when Debian's ROS is installed, to a Debian rospy one. p50/p90/p99 in ms.
- Load: --rate Hz of those small messages for --seconds to --clients roslibjs clients (one Node
  process): per client the messages received of those published, and the frames the bridge
  says it dropped for each (past ~max_queue_frames, 1000 by default).
- A stalled client: one that subscribes to 20 Hz of 1 MB messages and reads nothing, beside a
  roslibjs client that reads: what the reader got, and the bridge's memory (VmRSS, VmHWM).
Needs node and tests/web/node_modules (scripts/install-web-peers.sh). Bounded: each part runs
--seconds plus start-up, then every process is stopped.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import socket
import statistics
import subprocess
import sys
import textwrap
import time
from pathlib import Path
from typing import Any

from bench_procs import free_port, stop
from kame_bytecode import compile_kame

REPO = Path(__file__).resolve().parents[1]
ROSLIB = REPO / "tests" / "web" / "node_modules" / "roslib" / "dist" / "RosLib.js"
CLIENTS_JS = Path(__file__).resolve().parent / "rosbridge_clients.mjs"
DEBIAN_PYTHON = "/usr/bin/python3"

PUBLISHER = """
import sys, time, rospy
from std_msgs.msg import String
rate, seconds, wanted = float(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3])
padding = ' ' + 'x' * int(sys.argv[4]) if len(sys.argv) > 4 else ''
rospy.init_node('bench_talker')
pub = rospy.Publisher('/bench', String, queue_size=1000)
while pub.get_num_connections() < wanted and not rospy.is_shutdown():
    rospy.sleep(0.01)
period, start, n = 1.0 / rate, time.monotonic(), 0
while time.monotonic() - start < seconds:
    pub.publish(String('%d %.6f%s' % (n, time.time(), padding)))
    n += 1
    delay = start + n * period - time.monotonic()
    if delay > 0:
        time.sleep(delay)
print('published', n, flush=True)
"""

SUBSCRIBER = """
import json, time, rospy
from std_msgs.msg import String
latencies = []
def heard(msg):
    latencies.append((time.time() - float(msg.data.split()[1])) * 1000.0)
rospy.init_node('bench_listener', anonymous=True)
rospy.Subscriber('/bench', String, heard, queue_size=1000)
print('ready', flush=True)
rospy.spin()
print(json.dumps(latencies), flush=True)
"""


def percentiles(values: list[float]) -> str:
    if len(values) < 2:
        return "n/a"
    cuts = statistics.quantiles(values, n=100)
    return f"p50 {cuts[49]:6.2f}  p90 {cuts[89]:6.2f}  p99 {cuts[98]:6.2f} ms  ({len(values)} messages)"


def wait_port(port: int, seconds: float = 30.0) -> None:
    deadline = time.monotonic() + seconds
    while True:
        try:
            socket.create_connection(("127.0.0.1", port), timeout=1).close()
            return
        except OSError:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.05)


def python(interpreter: str, code: str, *args: str, env: dict[str, str]) -> subprocess.Popen[str]:
    return subprocess.Popen([interpreter, "-c", textwrap.dedent(code), *args], env=env, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)


def node_clients(url: str, clients: int, seconds: float, env: dict[str, str]) -> subprocess.Popen[str]:
    proc = subprocess.Popen(["node", str(CLIENTS_JS), url, "/bench", str(clients), str(seconds)],
                            env={**env, "ROSLIB": str(ROSLIB)}, text=True, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE)
    assert proc.stderr is not None
    line = proc.stderr.readline()
    assert line.strip() == "subscribed", line + proc.stderr.read()
    return proc


def latency(url: str, options: argparse.Namespace, env: dict[str, str], debian_env: dict[str, str] | None) -> None:
    listeners = {"kame rospy (TCPROS)": python(sys.executable, SUBSCRIBER, env=env)}
    if debian_env is not None:
        listeners["Debian rospy (TCPROS)"] = python(DEBIAN_PYTHON, SUBSCRIBER, env=debian_env)
    for proc in listeners.values():
        assert proc.stdout is not None and proc.stdout.readline().strip() == "ready"
    browser = node_clients(url, 1, options.seconds + 3, env)
    publisher = python(sys.executable, PUBLISHER, str(options.latency_rate), str(options.seconds),
                       str(1 + len(listeners)), env=env)
    publisher.communicate(timeout=options.seconds + 60)
    out, _ = browser.communicate(timeout=options.seconds + 30)
    seen = json.loads(out)[0]
    print(f"  roslibjs (Node) through the bridge  {percentiles(seen['latencies'][1:])}")
    for label, proc in listeners.items():
        stop(proc)
        assert proc.stdout is not None
        values = json.loads(proc.stdout.read().strip().splitlines()[-1])
        print(f"  {label:35s} {percentiles(values[1:])}")


def load(url: str, options: argparse.Namespace, env: dict[str, str], bridge_log: Path) -> None:
    clients = node_clients(url, options.clients, options.seconds + 3, env)
    publisher = python(sys.executable, PUBLISHER, str(options.rate), str(options.seconds), "1", env=env)
    published_out, _ = publisher.communicate(timeout=options.seconds + 60)
    published = int(published_out.split()[1])
    out, _ = clients.communicate(timeout=options.seconds + 30)
    seen = json.loads(out)
    received = [c["received"] for c in seen]
    print(f"  published {published} in {options.seconds:.0f} s ({published / options.seconds:.0f} Hz); "
          f"received per client: min {min(received)}, max {max(received)} "
          f"({min(received) / published:.1%} .. {max(received) / published:.1%})")
    all_latencies = [v for c in seen for v in c["latencies"]]
    print(f"  latency over all clients            {percentiles(all_latencies)}")
    time.sleep(1.0)  # the bridge logs each client's counts as it goes
    dropped = [int(m) for m in re.findall(r"frames sent to it, (\d+) dropped", bridge_log.read_text())]
    print(f"  frames the bridge dropped, per client: {dropped[-options.clients:]}")


def stalled(url: str, options: argparse.Namespace, env: dict[str, str], bridge_pid: int) -> None:
    """A client that subscribes to 1 MB messages and then reads nothing, beside one that reads."""
    from websockets.sync.client import connect

    before = _vm(bridge_pid, "VmRSS")
    with connect(url, max_queue=1, open_timeout=20) as stuck:
        stuck.send(json.dumps({"op": "subscribe", "topic": "/bench", "type": "std_msgs/String"}))
        reader = node_clients(url, 1, options.seconds + 3, env)
        publisher = python(sys.executable, PUBLISHER, "20", str(options.seconds), "1", str(1_000_000), env=env)
        published_out, _ = publisher.communicate(timeout=options.seconds + 60)
        out, _ = reader.communicate(timeout=options.seconds + 30)
        during = _vm(bridge_pid, "VmRSS")
    published = int(published_out.split()[1])
    print(f"  published {published} messages of 1 MB; the reading client got {json.loads(out)[0]['received']}; "
          f"bridge VmRSS {before / 1024:.0f} MB before, {during / 1024:.0f} MB with the stalled client "
          f"(its queue: 64 MiB at most), peak VmHWM {_vm(bridge_pid, 'VmHWM') / 1024:.0f} MB")


def _vm(pid: int, field: str) -> int:
    with open(f"/proc/{pid}/status") as status:
        return next(int(line.split()[1]) for line in status if line.startswith(field))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--latency-rate", type=float, default=50.0)
    parser.add_argument("--rate", type=float, default=1000.0)
    parser.add_argument("--clients", type=int, default=10)
    options = parser.parse_args()
    if not ROSLIB.is_file():
        sys.exit(f"no roslib at {ROSLIB}: run scripts/install-web-peers.sh")
    compile_kame()
    port, ws_port = free_port(), free_port()
    home = Path("/tmp") / f"kame-rosbridge-bench-{os.getpid()}"
    home.mkdir(parents=True, exist_ok=True)
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
    env.update(ROS_MASTER_URI=f"http://127.0.0.1:{port}/", ROS_HOSTNAME="127.0.0.1", ROS_HOME=str(home))
    debian_env = None
    if Path(DEBIAN_PYTHON).exists() and subprocess.run([DEBIAN_PYTHON, "-c", "import rospy"],
                                                      capture_output=True).returncode == 0:
        debian_env = {k: v for k, v in env.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
        debian_env["PATH"] = "/usr/bin:/bin"
    master = subprocess.Popen([sys.executable, "-m", "kame.cli.rosmaster", "--core", "-p", str(port)], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    bridge_log = home / "bridge.log"
    procs: list[subprocess.Popen[Any]] = [master]
    try:
        wait_port(port)
        with bridge_log.open("w") as sink:
            bridge = subprocess.Popen([sys.executable, "-m", "kame.cli.rosrun", "rosbridge_server",
                                       "rosbridge_websocket", f"_port:={ws_port}"], env=env, stdout=sink,
                                      stderr=subprocess.STDOUT)
        procs.insert(0, bridge)
        wait_port(ws_port)
        url = f"ws://127.0.0.1:{ws_port}"
        print(f"kame rosbridge, load average {os.getloadavg()[0]:.1f} ({os.cpu_count()} cores)")
        print(f"Latency, publish() to the client's callback, {options.latency_rate:.0f} Hz "
              f"for {options.seconds:.0f} s:")
        latency(url, options, env, debian_env)
        print(f"Load: {options.clients} roslibjs clients, {options.rate:.0f} Hz of small messages:")
        load(url, options, env, bridge_log)
        print("A client that stops reading, 20 Hz of 1 MB messages:")
        stalled(url, options, env, bridge.pid)
        print(f"load average after: {os.getloadavg()[0]:.1f}")
    finally:
        for proc in procs:
            stop(proc)


if __name__ == "__main__":
    main()
