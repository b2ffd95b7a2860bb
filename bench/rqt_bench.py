#!/usr/bin/env python3
"""rqt tools benchmark: rqt_console under a log flood, rqt_plot with 10 series at 1 kHz, and an
rqt_graph refresh of a 200-node graph (run with the project venv's python; Qt offscreen).

  .venv/bin/python bench/rqt_bench.py [--seconds 5] [--only console,plot,graph]

console: a kame node publishes rosgraph_msgs/Log on /rosout_agg at --log-rate a second (absolute
         schedule); the console window (offscreen) with its feed and 20,000-message store takes
         them. Reports messages shown against sent, the table's rows and the store against its
         bound, the longest stall of the window's event loop (a 10 ms timer's worst gap) and CPU.
plot:    one process publishes 10 std_msgs/Float64 topics at --plot-rate each; the plot window
         (offscreen) plots all ten. Reports frames drawn a second, points kept, the worst stall
         and CPU.
graph:   one process runs 200 kame nodes in a chain (node i publishes /chain/i, subscribes
         /chain/i-1); rqt_graph's source fetches the graph 5 times. Reports the fetch time
         (median, max), the nodes and links seen, and what the window's redraw does after a fetch
         (the scene model, its layout and the Qt items) in "Nodes only" and "Nodes/Topics (all)";
         a refresh in the window is the fetch plus that redraw.
CPU is this process's CPU seconds per wall second (all its threads: the subscribers' and the
window's) while the window runs its own Qt event loop, as the tool does; the window thread's own
share is given beside it. With RQT_BENCH_PROFILE=1 that loop runs under cProfile (to stderr).
Each part gets a fresh kame master on a free loopback port; every process is stopped by its PID.
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

from bench_procs import free_port
from kame_bytecode import compile_kame

REPO = Path(__file__).resolve().parents[1]
VENV_BIN = REPO / ".venv" / "bin"

NODE = r"""
import os, sys, time
from kame.node.node import Node, NodeConfig
def node(name):
    return Node(NodeConfig(name, os.environ['ROS_MASTER_URI'], '127.0.0.1', '127.0.0.1'))
"""

LOG_FEEDER = NODE + r"""
from rosgraph_msgs.msg import Log
from kame.node.topics import serialize_frame
rate, seconds = float(sys.argv[1]), float(sys.argv[2])
n = node('/bench_logger')
pub = n.advertise('/rosout_agg', 'rosgraph_msgs/Log', Log._md5sum, Log._full_text, queue_size=100000)
while not pub.links:
    time.sleep(0.01)
time.sleep(0.5)
frames = [serialize_frame(Log(level=(2, 4, 8)[i % 3], name='/bench_logger', msg='message %d' % i, file='/x.py',
                              function='f', line=i, topics=['/rosout'])) for i in range(1000)]
sent, start = 0, time.monotonic()
while time.monotonic() - start < seconds:
    for _ in range(10):  # bursts of 10, on an absolute schedule
        pub.publish_frame(frames[sent % 1000])
        sent += 1
    delay = start + sent / rate - time.monotonic()
    if delay > 0:
        time.sleep(delay)
print('SENT %d %.3f' % (sent, time.monotonic() - start), flush=True)
time.sleep(2)
n.shutdown()
"""

PLOT_FEEDER = NODE + r"""
import math
from std_msgs.msg import Float64
from kame.node.topics import serialize_frame
rate, seconds, topics = float(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3])
n = node('/bench_signals')
pubs = [n.advertise('/signal%d' % k, 'std_msgs/Float64', Float64._md5sum, Float64._full_text, queue_size=10000)
        for k in range(topics)]
while not all(p.links for p in pubs):
    time.sleep(0.01)
time.sleep(0.5)
sent, start = 0, time.monotonic()
while time.monotonic() - start < seconds:
    for k, p in enumerate(pubs):
        p.publish_frame(serialize_frame(Float64(math.sin(sent / rate * (k + 1)))))
    sent += 1
    delay = start + sent / rate - time.monotonic()
    if delay > 0:
        time.sleep(delay)
print('SENT %d %.3f' % (sent * topics, time.monotonic() - start), flush=True)
time.sleep(2)
n.shutdown()
"""

CHAIN = NODE + r"""
from std_msgs.msg import Int64
count = int(sys.argv[1])
nodes = []
for i in range(count):
    n = node('/chain_node_%d' % i)
    n.advertise('/chain/%d' % i, 'std_msgs/Int64', Int64._md5sum, Int64._full_text)
    if i:
        n.subscribe('/chain/%d' % (i - 1), 'std_msgs/Int64', Int64._md5sum, Int64._full_text, lambda f, h: None)
    nodes.append(n)
print('READY', flush=True)
sys.stdin.read()
for n in nodes:
    n.shutdown()
"""


class Procs:
    def __init__(self) -> None:
        self.procs: list[subprocess.Popen[str]] = []

    def start(self, args: list[str], env: dict[str, str], stdin: int | None = None) -> subprocess.Popen[str]:
        proc = subprocess.Popen(args, env=env, stdin=stdin, stdout=subprocess.PIPE, text=True, start_new_session=True)
        self.procs.append(proc)
        return proc

    def stop(self) -> None:
        for proc in reversed(self.procs):
            if proc.poll() is None:
                os.kill(proc.pid, signal.SIGINT)
                try:
                    proc.wait(5)
                except subprocess.TimeoutExpired:
                    os.kill(proc.pid, signal.SIGKILL)
                    proc.wait(5)


def with_master(run):  # type: ignore[no-untyped-def]
    port = free_port()
    home = tempfile.mkdtemp(prefix="rqt-bench-")
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
    env.update(ROS_MASTER_URI=f"http://127.0.0.1:{port}/", ROS_HOSTNAME="127.0.0.1", ROS_HOME=home,
               QT_QPA_PLATFORM="offscreen")
    os.environ.update(env)
    procs = Procs()
    try:
        procs.start([str(VENV_BIN / "rosmaster"), "--core", "-p", str(port)], env)
        import xmlrpc.client

        deadline = time.monotonic() + 10
        while True:
            try:
                xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"]).getPid("/bench")
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.05)
        return run(env, procs)
    finally:
        procs.stop()


class Stalls:
    """The worst gap between ticks of a 10 ms timer: how long the window's event loop was busy."""

    def __init__(self) -> None:
        from PySide6.QtCore import QTimer

        self.worst = 0.0
        self.last = time.monotonic()
        self.timer = QTimer()
        self.timer.timeout.connect(self._tick)
        self.timer.start(10)

    def _tick(self) -> None:
        now = time.monotonic()
        self.worst = max(self.worst, now - self.last)
        self.last = now


def run_for(app, seconds: float, until) -> None:  # type: ignore[no-untyped-def]
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline and not until():
        app.processEvents()
        time.sleep(0.002)


def thread_seconds() -> dict[str, float]:
    """CPU seconds of each live thread of this process so far, by thread name (Linux /proc)."""
    tick = os.sysconf("SC_CLK_TCK")
    out: dict[str, float] = {}
    for thread in threading.enumerate():
        try:
            fields = Path(f"/proc/self/task/{thread.native_id}/stat").read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        out[thread.name] = out.get(thread.name, 0.0) + (int(fields[11]) + int(fields[12])) / tick
    return out


class Usage:
    """CPU seconds per wall second over a measured stretch: the whole process's, the window's
    thread, and the subscribers' receiving threads (kame-sub/<topic>) together."""

    def __init__(self) -> None:
        self.cpu, self.window, self.wall = time.process_time(), time.thread_time(), time.monotonic()
        self._threads = thread_seconds()
        self.subscribers = 0.0

    def stop(self) -> None:
        self.cpu = time.process_time() - self.cpu
        self.window = time.thread_time() - self.window
        self.wall = time.monotonic() - self.wall
        self.subscribers = sum(seconds - self._threads.get(name, 0.0) for name, seconds in thread_seconds().items()
                               if name.startswith("kame-sub"))

    def __str__(self) -> str:
        def share(seconds: float) -> str:
            return f"{100 * seconds / self.wall:.0f}%"

        return (f"CPU {share(self.cpu)} (window thread {share(self.window)}, receiving threads "
                f"{share(self.subscribers)})")


def event_loop(seconds: float) -> None:
    """The application's own event loop (as the tool's app.exec() runs it) for `seconds`."""
    from PySide6.QtCore import QEventLoop, QTimer

    loop = QEventLoop()
    QTimer.singleShot(int(seconds * 1000), loop.quit)
    loop.exec()


def measured(seconds: float) -> Usage:
    """The window's event loop for `seconds` and what it cost; with RQT_BENCH_PROFILE set, under
    cProfile (stderr)."""
    usage = Usage()
    if not os.environ.get("RQT_BENCH_PROFILE"):
        event_loop(seconds)
    else:
        import cProfile
        import pstats

        profile = cProfile.Profile()
        profile.runcall(event_loop, seconds)
        pstats.Stats(profile, stream=sys.stderr).sort_stats("tottime").print_stats(15)
    usage.stop()
    return usage


def bench_console(args: argparse.Namespace, env: dict[str, str], procs: Procs) -> str:
    from kame.rqt.console_model import LogView
    from kame.rqt.console_source import LogFeed
    from kame.rqt.console_window import ConsoleWindow, application
    from kame.rqt.ros_node import start_node

    app = application("bench")
    window = ConsoleWindow(LogView())
    window.resize(1100, 600)
    window.show()
    node = start_node("console", {})
    feed = LogFeed(node, window.messages_ready.emit)
    window.take = feed.take
    feeder = procs.start([sys.executable, "-c", LOG_FEEDER, str(args.log_rate), str(args.seconds)], env)
    run_for(app, 30, lambda: window.view.received > 0)  # connected and flowing
    stalls = Stalls()
    usage = measured(args.seconds)
    run_for(app, 20, lambda: feeder.poll() is not None)
    node.shutdown("bench over")
    sent = _sent(feeder)
    return (f"console  {args.log_rate:>7.0f} msg/s: shown {window.view.received:>7d} of {sent:>7d} sent; "
            f"{window.model.rowCount()} rows in the table, {window.view.stored_count} stored (bound "
            f"{window.view.capacity}); worst event-loop stall {stalls.worst * 1e3:5.0f} ms; {usage}")


def _sent(proc: subprocess.Popen[str]) -> int:
    out = proc.stdout.read() if proc.stdout is not None else ""
    return next((int(line.split()[1]) for line in out.splitlines() if line.startswith("SENT")), 0)


def bench_plot(args: argparse.Namespace, env: dict[str, str], procs: Procs) -> str:
    from kame.rqt.console_window import application
    from kame.rqt.plot_source import PlotSource
    from kame.rqt.plot_window import PlotWindow
    from kame.rqt.ros_node import start_node

    app = application("bench")
    node = start_node("plot", {})
    source = PlotSource(node)
    feeder = procs.start([sys.executable, "-c", PLOT_FEEDER, str(args.plot_rate), str(args.seconds), "10"], env)
    while len(source.topic_types()) < 10:
        time.sleep(0.05)
    window = PlotWindow(source)
    window.resize(1200, 700)
    window.show()
    for k in range(10):
        window.add_series(f"/signal{k}/data")
    frames = 0
    peaks = source.peaks

    def counted(*a):  # type: ignore[no-untyped-def]
        nonlocal frames
        frames += 1
        return peaks(*a)

    source.peaks = counted  # type: ignore[method-assign]
    run_for(app, 30, lambda: all(len(t) for t, _ in source.data().values()))  # every series flowing
    frames = 0
    stalls = Stalls()
    usage = measured(args.seconds)
    drawn = frames
    run_for(app, 20, lambda: feeder.poll() is not None)
    kept = sum(len(t) for t, _ in source.data().values())
    node.shutdown("bench over")
    sent = _sent(feeder)
    return (f"plot     10 x {args.plot_rate:.0f} Hz: {drawn / usage.wall:5.1f} frames/s; {kept} of {sent} points kept; "
            f"worst stall {stalls.worst * 1e3:5.0f} ms; {usage}")


def bench_graph(args: argparse.Namespace, env: dict[str, str], procs: Procs) -> str:
    from kame.rqt.graph_model import GraphOptions, build_scene
    from kame.rqt.graph_source import GraphSource

    chain = procs.start([sys.executable, "-c", CHAIN, str(args.nodes)], env, stdin=subprocess.PIPE)
    assert chain.stdout is not None and chain.stdout.readline().strip() == "READY"
    source = GraphSource(env["ROS_MASTER_URI"])
    deadline = time.monotonic() + 30
    while len(source.fetch().links) < args.nodes - 1 and time.monotonic() < deadline:
        time.sleep(0.2)
    times = []
    for _ in range(5):
        start = time.monotonic()
        snapshot = source.fetch()
        times.append(time.monotonic() - start)
    from kame.rqt.console_window import application
    from kame.rqt.graph_layout import layout
    from kame.rqt.graph_model import Mode
    from kame.rqt.graph_window import GraphScene, graph_font, measure_with

    application("bench")
    font = graph_font()
    drawn = []
    for mode in (Mode.NODES_ONLY, Mode.NODES_TOPICS_ALL):
        # what the window's redraw does with a fetched snapshot, up to the items Qt paints
        started = time.monotonic()
        scene = GraphScene(layout(build_scene(snapshot, GraphOptions(mode=mode)), measure_with(font)), font)
        drawn.append(f"{mode.value} {(time.monotonic() - started) * 1e3:.0f} ms ({len(scene.items())} items)")
    source.close()
    assert chain.stdin is not None
    chain.stdin.close()
    chain.wait(60)  # shutting 200 nodes down
    times.sort()
    return (f"graph    {len(snapshot.nodes)} nodes, {len(snapshot.links)} links: fetch median "
            f"{times[2] * 1e3:.0f} ms, max {times[-1] * 1e3:.0f} ms; scene, layout and items: {'; '.join(drawn)}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=5.0)
    parser.add_argument("--log-rate", type=float, default=10_000.0)
    parser.add_argument("--plot-rate", type=float, default=1000.0)
    parser.add_argument("--nodes", type=int, default=200)
    parser.add_argument("--only", default="console,plot,graph")
    args = parser.parse_args()
    compile_kame()
    parts = {"console": bench_console, "plot": bench_plot, "graph": bench_graph}
    for name in args.only.split(","):
        print(with_master(lambda env, procs, name=name: parts[name](args, env, procs)), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
