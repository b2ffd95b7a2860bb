#!/usr/bin/env python3
"""Command-line tool benchmark: `rostopic hz` accuracy and `rostopic echo` keeping up (stdlib only).

Each measurement gets a fresh master on a free loopback port; every process is started in its
own process group and stopped by its PID. The same publisher and the same tool commands run
for each implementation: kame (the project venv: its rostopic, rospy and master) and, where
Debian's ROS 1 is installed, rospy (Debian's rostopic, rospy and rosmaster).

  python3 bench/tools_bench.py [--seconds 6] [--rate 1000] [--echo-rate 10000]

hz:   a publisher at --rate Hz (on an absolute schedule), `rostopic hz` for --seconds; the last
      average it prints, against the nominal rate and the rate the publisher really achieved.
echo: a publisher sending --echo-rate numbered messages a second, `rostopic echo -p` for
      --seconds; messages echoed against messages sent, and gaps in the sequence.
"""

from __future__ import annotations

import argparse
import itertools
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
import xmlrpc.client
from pathlib import Path

from bench_procs import free_port
from kame_bytecode import compile_kame

REPO = Path(__file__).resolve().parents[1]
VENV_BIN = REPO / ".venv" / "bin"

PUBLISHER = r"""
import sys, time, rospy
from std_msgs.msg import Int64
rate_hz, seconds = float(sys.argv[1]), float(sys.argv[2])
rospy.init_node('bench_source')
pub = rospy.Publisher('/bench_topic', Int64, queue_size=100000)
while pub.get_num_connections() < 1:
    time.sleep(0.01)
time.sleep(0.5)
period = 1.0 / rate_hz
n, start = 0, time.monotonic()
while not rospy.is_shutdown() and time.monotonic() - start < seconds:
    pub.publish(n)
    n += 1
    delay = start + n * period - time.monotonic()  # absolute schedule: the topic holds the rate
    if delay > 0:
        time.sleep(delay)
print('SENT %d %.6f' % (n, time.monotonic() - start), flush=True)
time.sleep(1.0)
"""


class Impl:
    def __init__(self, name: str, python: str, master: list[str], rostopic: list[str]) -> None:
        self.name, self.python, self.master, self.rostopic = name, python, master, rostopic


def implementations() -> list[Impl]:
    found = []
    if (VENV_BIN / "rostopic").exists():
        found.append(Impl("kame", str(VENV_BIN / "python"), [str(VENV_BIN / "rosmaster"), "--core", "-p"],
                          [str(VENV_BIN / "python"), str(VENV_BIN / "rostopic")]))
    if os.path.exists("/usr/bin/rostopic") and os.path.exists("/usr/bin/rosmaster"):
        found.append(Impl("rospy", "/usr/bin/python3", ["/usr/bin/rosmaster", "--core", "-p"],
                          ["/usr/bin/python3", "/usr/bin/rostopic"]))
    return found


def start(args: list[str], env: dict[str, str], out: Path) -> subprocess.Popen[bytes]:
    with open(out, "wb") as sink:
        return subprocess.Popen(args, env=env, stdout=sink, stderr=subprocess.STDOUT, start_new_session=True)


def stop(proc: subprocess.Popen[bytes]) -> None:
    if proc.poll() is None:
        try:
            os.killpg(proc.pid, signal.SIGINT)
            proc.wait(5)
        except (subprocess.TimeoutExpired, ProcessLookupError):
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            proc.wait(5)


def run(impl: Impl, tool_args: list[str], rate: float, seconds: float) -> tuple[str, str]:
    """Start a master, the publisher and the tool; return (publisher output, tool output)."""
    work = Path(tempfile.mkdtemp(prefix=f"toolbench-{impl.name}-"))
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
    env.update(ROS_MASTER_URI=uri, ROS_HOSTNAME="127.0.0.1", ROS_HOME=str(work), PYTHONUNBUFFERED="1")
    procs = [start([*impl.master, str(port)], env, work / "master.out")]
    try:
        deadline = time.monotonic() + 15
        while True:
            try:
                xmlrpc.client.ServerProxy(uri).getPid("/bench")
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.05)
        tool = start([*impl.rostopic, *tool_args], env, work / "tool.out")
        procs.append(tool)
        source = start([impl.python, "-c", PUBLISHER, str(rate), str(seconds)], env, work / "source.out")
        procs.append(source)
        source.wait(seconds + 60)
        time.sleep(0.5)
    finally:
        for proc in reversed(procs):
            stop(proc)
    return (work / "source.out").read_text(), (work / "tool.out").read_text(errors="replace")


def sent(publisher_output: str) -> tuple[int, float]:
    match = re.search(r"SENT (\d+) ([\d.]+)", publisher_output)
    if match is None:
        raise RuntimeError(f"publisher failed:\n{publisher_output}")
    return int(match.group(1)), float(match.group(2))


def measure_hz(impl: Impl, rate: float, seconds: float) -> tuple[float, float]:
    pub_out, tool_out = run(impl, ["hz", "/bench_topic"], rate, seconds)
    count, span = sent(pub_out)
    rates = [float(r) for r in re.findall(r"average rate: ([\d.]+)", tool_out)]
    if not rates:
        raise RuntimeError(f"rostopic hz printed no rate:\n{tool_out[-2000:]}")
    return rates[-1], count / span


def measure_echo(impl: Impl, rate: float, seconds: float) -> tuple[int, int, int]:
    pub_out, tool_out = run(impl, ["echo", "-p", "/bench_topic"], rate, seconds)
    count, _ = sent(pub_out)
    values = [int(line.split(",")[1]) for line in tool_out.splitlines() if re.fullmatch(r"\d+,\d+", line)]
    gaps = sum(1 for a, b in itertools.pairwise(values) if b != a + 1)
    return len(values), count, gaps


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=6.0)
    parser.add_argument("--rate", type=float, default=1000.0)
    parser.add_argument("--echo-rate", type=float, default=10000.0)
    args = parser.parse_args()
    compile_kame()
    rows = []
    for impl in implementations():
        print(f"{impl.name}: rostopic hz at {args.rate:g} Hz ...", file=sys.stderr)
        reported, actual = measure_hz(impl, args.rate, args.seconds)
        print(f"{impl.name}: rostopic echo at {args.echo_rate:g} Hz ...", file=sys.stderr)
        echoed, count, gaps = measure_echo(impl, args.echo_rate, args.seconds)
        rows.append((impl.name, reported, actual, echoed, count, gaps))
    print(f"{'impl':8} {'hz reported':>12} {'vs nominal':>10} {'published':>10}   {'echoed':>8} {'sent':>8} "
          f"{'kept':>6} {'gaps':>5}")
    for name, reported, actual, echoed, count, gaps in rows:
        print(f"{name:8} {reported:12.1f} {100 * (reported - args.rate) / args.rate:+9.2f}% {actual:10.1f}   "
              f"{echoed:8d} {count:8d} {100 * echoed / count:5.1f}% {gaps:5d}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
