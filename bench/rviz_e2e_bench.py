"""rviz's latency from message to pixels, end to end (issue 18): kame's master, the real `rviz`
window (its own process, on a private Xvfb when no DISPLAY is set, Mesa's software GL) and a
publisher process stamping each message's header with the wall time just before publish().
Scenes: one marker at 7 Hz (the floor), a 2,000-marker MarkerArray at 3 Hz, a 300k-point
PointCloud2 at 10 Hz, both of those at once, and a 2,000x2,000 map at 1 Hz.
rviz writes when each message's first frame was swapped to the screen (KAME_RVIZ_STATS, see
kame.rviz.shown_log), so a latency here is serialization and TCPROS (or shared memory) transport,
decoding, the wait for the window's frame, building the scene, drawing and Qt's composition
and buffer swap. Reported per scene and topic: median, p90 and max latency (the first message
of each topic, which allocates its display's GL buffers, separately), messages shown of those
published (a newer one replaces one not yet taken), frames swapped per second (rviz paints
only when something changed: at most the message rate) and rviz's CPU (% of one core).

    .venv/bin/python bench/rviz_e2e_bench.py [--seconds 20] [--runs 3] [--scene one|markers|cloud|both|map]
"""

from __future__ import annotations

import argparse
import os
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from bench_procs import cpu_seconds, free_port, stop
from kame_bytecode import compile_kame
from rviz_bench import with_display

BIN = Path(sys.executable).parent
MARKERS, CLOUD, ONE, MAP = "/e2e/markers", "/e2e/cloud", "/e2e/one", "/e2e/map"
# one marker at 7 Hz (not a divisor of the frame rate): the floor, where waiting for a frame shows
RATES = {MARKERS: 3.0, CLOUD: 10.0, ONE: 7.0, MAP: 1.0}
SCENES = {"one": (ONE,), "markers": (MARKERS,), "cloud": (CLOUD,), "both": (MARKERS, CLOUD), "map": (MAP,)}
# the view 1280x720 beside rviz's Displays panel, tool bar, menus and status bar (as Qt lays them out offscreen)
CONFIG = """Visualization Manager:
  Global Options:
    Fixed Frame: map
    Frame Rate: 30
  Displays:
{displays}
Window Geometry:
  Width: 1604
  Height: 769
"""
DISPLAYS = {
    MARKERS: f"    - Class: rviz/MarkerArray\n      Name: MarkerArray\n      Enabled: true\n"
             f"      Marker Topic: {MARKERS}\n",
    CLOUD: f"    - Class: rviz/PointCloud2\n      Name: PointCloud2\n      Enabled: true\n      Topic: {CLOUD}\n",
    ONE: f"    - Class: rviz/MarkerArray\n      Name: One\n      Enabled: true\n      Marker Topic: {ONE}\n",
    MAP: f"    - Class: rviz/Map\n      Name: Map\n      Enabled: true\n      Topic: {MAP}\n",
}


def publish(topics: list[str], seconds: float) -> int:
    """The publisher process: waits for rviz's subscriptions, then publishes each topic at its
    rate for `seconds`, stamping each message as it goes out; prints how many of each."""
    import rospy
    import tf2_ros
    from geometry_msgs.msg import TransformStamped
    from nav_msgs.msg import OccupancyGrid
    from sensor_msgs.msg import PointCloud2
    from visualization_msgs.msg import MarkerArray

    from rviz_bench import cloud, grid_map, marker_array

    rospy.init_node("rviz_e2e_publisher")
    static = TransformStamped()  # rviz's fixed frame must exist in tf
    static.header.frame_id, static.child_frame_id = "map", "base_link"
    static.transform.rotation.w = 1.0
    broadcaster = tf2_ros.StaticTransformBroadcaster()
    broadcaster.sendTransform(static)
    messages = {MARKERS: marker_array(2000), CLOUD: cloud(300_000), ONE: marker_array(1), MAP: grid_map(2000)}
    types = {MARKERS: MarkerArray, CLOUD: PointCloud2, ONE: MarkerArray, MAP: OccupancyGrid}
    publishers = {topic: rospy.Publisher(topic, types[topic], queue_size=1)
                  for topic in topics}
    deadline = time.monotonic() + 60
    while any(p.get_num_connections() == 0 for p in publishers.values()):
        if time.monotonic() > deadline:
            print("rviz never subscribed", flush=True)
            return 1
        time.sleep(0.05)
    time.sleep(1.0)  # rviz's decoder and window settled on the subscription before the first message
    print("start", flush=True)
    start = time.monotonic()
    due = dict.fromkeys(topics, start)
    sent = dict.fromkeys(topics, 0)
    while True:
        topic = min(due, key=lambda t: due[t])
        if due[topic] >= start + seconds:
            break
        time.sleep(max(0.0, due[topic] - time.monotonic()))
        message = messages[topic]
        stamp = rospy.Time.from_sec(time.time())
        for stamped in getattr(message, "markers", [message]):
            stamped.header.stamp = stamp
        publishers[topic].publish(message)
        sent[topic] += 1
        due[topic] += 1 / RATES[topic]
    print("sent", " ".join(f"{topic} {count}" for topic, count in sent.items()), flush=True)
    return 0


def wait_for_master(port: int) -> None:
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        try:
            socket.create_connection(("127.0.0.1", port), 0.5).close()
            return
        except OSError:
            time.sleep(0.05)
    raise SystemExit("the master never listened")


def run(scene: str, seconds: float, work: Path) -> str:
    topics = list(SCENES[scene])
    port = free_port()
    env = {**os.environ, "ROS_MASTER_URI": f"http://127.0.0.1:{port}/", "ROS_HOSTNAME": "127.0.0.1",
           "ROS_HOME": str(work)}
    config, shown = work / f"{scene}.rviz", work / f"{scene}.shown"
    config.write_text(CONFIG.format(displays="".join(DISPLAYS[t] for t in topics)))
    shown.unlink(missing_ok=True)
    master = subprocess.Popen([str(BIN / "rosmaster"), "--core", "-p", str(port)], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, text=True)
    procs = [master]
    try:
        wait_for_master(port)
        rviz = subprocess.Popen([str(BIN / "rviz"), "-d", str(config)], env={**env, "KAME_RVIZ_STATS": str(shown)},
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, text=True)
        procs.append(rviz)
        publisher = subprocess.Popen([sys.executable, __file__, "--publish", ",".join(topics), "--seconds",
                                      str(seconds)], env=env, stdout=subprocess.PIPE, text=True)
        procs.append(publisher)
        assert publisher.stdout is not None
        line = publisher.stdout.readline()
        if line.strip() != "start":
            return f"| {scene} | publisher: {line.strip() or 'ended'} |"
        cpu, began = cpu_seconds(rviz.pid), time.monotonic()
        line = publisher.stdout.readline().split()
        cpu, elapsed = cpu_seconds(rviz.pid) - cpu, time.monotonic() - began
        sent = dict(zip(line[1::2], (int(n) for n in line[2::2]), strict=True))
        # the last message's frame: shown within a second on any machine this runs on, or lost
        deadline = time.monotonic() + 3
        while time.monotonic() < deadline and len(shown_lines(shown)) < sum(sent.values()):
            time.sleep(0.1)
        stop(rviz)
        return report(scene, shown_lines(shown), sent, cpu / elapsed, elapsed)
    finally:
        for proc in reversed(procs):
            stop(proc)


def shown_lines(path: Path) -> list[tuple[str, float, float, float]]:
    if not path.exists():
        return []
    rows = []
    for line in path.read_text().splitlines():
        parts = line.split()
        if len(parts) == 4:
            rows.append((parts[0], float(parts[1]), float(parts[2]), float(parts[3])))
    return rows


def report(scene: str, rows: list[tuple[str, float, float, float]], sent: dict[str, int], cpu: float,
           elapsed: float) -> str:
    swaps = len({row[3] for row in rows})
    cells = []
    for topic in sent:
        mine = sorted((row for row in rows if row[0] == topic), key=lambda row: row[1])
        if not mine:
            cells.append(f"{topic}: nothing shown of {sent[topic]}")
            continue
        first = 1000 * (mine[0][3] - mine[0][1])
        later = 1000 * np.array([row[3] - row[1] for row in mine[1:]]) if len(mine) > 1 else np.array([first])
        waited = 1000 * np.array([row[3] - row[2] for row in mine[1:]]) if len(mine) > 1 else np.array([0.0])
        cells.append(f"{topic.rsplit('/', 1)[1]} {len(mine)}/{sent[topic]}: median {np.median(later):.0f}, "
                     f"p90 {np.percentile(later, 90):.0f}, max {later.max():.0f} (first {first:.0f}; "
                     f"taken to shown median {np.median(waited):.0f})")
    return f"| {scene} | {'; '.join(cells)} | {swaps / elapsed:.1f} | {100 * cpu:.0f} |"


def loadavg() -> str:
    return " ".join(Path("/proc/loadavg").read_text().split()[:3])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--scene", choices=sorted(SCENES), action="append")
    parser.add_argument("--publish", help=argparse.SUPPRESS)  # the publisher process: its topics
    options = parser.parse_args()
    if options.publish:
        return publish(options.publish.split(","), options.seconds)
    compile_kame()
    print("| scene | per topic: shown/sent, latency ms | frames swapped/s | rviz CPU % |")
    print("|---|---|---|---|")
    with tempfile.TemporaryDirectory(prefix="rviz-e2e-") as work:
        for scene in options.scene or list(SCENES):
            for _ in range(options.runs):
                before = loadavg()
                row = run(scene, options.seconds, Path(work))
                print(f"{row} load {before} -> {loadavg()}", flush=True)
    return 0


if __name__ == "__main__":
    if "--publish" in sys.argv:
        sys.exit(main())
    sys.exit(with_display(main))
