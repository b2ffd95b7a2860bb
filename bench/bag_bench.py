"""rosbag benchmark: kame against Debian's rosbag in the same run.

1. `rosbag info` and a full read (every message deserialized) of a large bag: 1M small
   messages (std_msgs/String at 1 kHz) and 1,000 sensor_msgs/Image of 1024x640 rgb8 (~2 MB),
   about 2 GB, read once before each measurement so that both run from the page cache; best
   of 5 (info) and of 2 (read). The bag is generated once into a cache under the system temp dir
   (<tmp>/kame-bench/bag_<n>.bag) and reused by later runs; --small-count picks a smaller one.
2. Record throughput: a kame publisher sends 1 kHz small messages and 30 Hz 6 MB images for
   --record-seconds; kame's `rosbag record` and Debian's C++ recorder each record one run;
   the table shows what each recorder got of what was published. --busy N runs N busy-loop
   processes meanwhile (a loaded machine: where recorders that need more CPU than they get
   start dropping).

3. `--play-only`: `rosbag play -i` of a smaller bag (by default 100k small messages and 100
   images) to one subscriber: the player's wall and CPU time, best of 3, and what the
   subscriber got.

Usage: .venv/bin/python bench/bag_bench.py [--small-count N] [--record-seconds S] [--skip-debian-read] [--busy N]
       .venv/bin/python bench/bag_bench.py --play-only
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from kame_bytecode import compile_kame

REPO = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
SYSTEM_PYTHON = "/usr/bin/python3"

READ = "import sys, rosbag\nn = 0\nfor _ in rosbag.Bag(sys.argv[1]).read_messages():\n    n += 1\nprint(n)\n"

PUBLISHER = r"""
import sys, time, rospy
from std_msgs.msg import String
from sensor_msgs.msg import Image
seconds = float(sys.argv[1])
rospy.init_node('bag_bench_pub', disable_signals=True)
small = rospy.Publisher('/small', String, queue_size=10000)
image = rospy.Publisher('/image', Image, queue_size=100)
img = Image(height=1024, width=2048, encoding='rgb8', step=2048 * 3, data=bytes(1024 * 2048 * 3))
deadline = time.monotonic() + 30
while (small.get_num_connections() == 0 or image.get_num_connections() == 0) and time.monotonic() < deadline:
    time.sleep(0.05)
time.sleep(1.0)
n_small = n_img = 0
start = time.monotonic()
while time.monotonic() - start < seconds:
    now = time.monotonic() - start
    while n_small < now * 1000:
        small.publish(String(data='msg %d' % n_small)); n_small += 1
    while n_img < now * 30:
        img.header.seq = n_img
        image.publish(img); n_img += 1
    time.sleep(0.0005)
time.sleep(2.0)
print(n_small, n_img, flush=True)
"""


SINK = r"""
import sys, rospy
rospy.init_node('bag_bench_sink', disable_signals=True)
got = [0, 0]
def count(m):
    got[0] += 1
    got[1] += len(m._buff)
rospy.Subscriber('/small', rospy.AnyMsg, count, queue_size=1000000)
rospy.Subscriber('/camera/image', rospy.AnyMsg, count, queue_size=1000)
print('ready', flush=True)
sys.stdin.read()
print(got[0], got[1], flush=True)
"""


def play_run(bag: Path, env: dict[str, str]) -> tuple[float, float, int, int]:
    """`rosbag play -i` of `bag` to one subscriber: (player wall s, player CPU s, messages and
    bytes the subscriber got)."""
    sink = subprocess.Popen([sys.executable, "-c", SINK], env=env, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                            text=True)
    try:
        assert sink.stdout is not None and sink.stdin is not None
        sink.stdout.readline()
        t0 = time.perf_counter()
        player = subprocess.Popen([str(BIN / "rosbag"), "play", "-i", "-q", "-d", "1", str(bag)], env=env,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        _, status, usage = os.wait4(player.pid, 0)
        wall = time.perf_counter() - t0 - 1.0  # less the -d 1 wait after advertising
        player.returncode = os.waitstatus_to_exitcode(status)
        if player.returncode != 0:
            raise RuntimeError(f"rosbag play exited with {player.returncode}")
        time.sleep(1.0)  # what is still in flight reaches the subscriber
        sink.stdin.close()
        n, size = (int(x) for x in sink.stdout.readline().split())
        return wall, usage.ru_utime + usage.ru_stime, n, size
    finally:
        if sink.poll() is None:
            os.kill(sink.pid, signal.SIGKILL)
        sink.wait()


def cache_dir() -> Path:
    d = Path(tempfile.gettempdir()) / "kame-bench"
    d.mkdir(exist_ok=True)
    return d


def make_bag(small_count: int, images: int) -> Path:
    path = cache_dir() / f"bag_{small_count}_{images}.bag"
    if path.exists():
        print(f"using cached bag {path} ({path.stat().st_size / 2**30:.2f} GiB)")
        return path
    from kame.bag.writer import BagWriter
    from kame.node.topics import serialize_payload
    from sensor_msgs.msg import Image
    from std_msgs.msg import String

    print(f"generating {path} (once; later runs reuse it) ...", flush=True)
    t0 = time.perf_counter()
    tmp = path.with_suffix(".tmp")
    w = BagWriter(tmp)
    cs = w.add_connection("/small", {"topic": "/small", "type": String._type, "md5sum": String._md5sum,
                                     "message_definition": String._full_text})
    ci = w.add_connection("/camera/image", {"topic": "/camera/image", "type": Image._type, "md5sum": Image._md5sum,
                                            "message_definition": Image._full_text})
    img = Image(height=640, width=1024, encoding="rgb8", step=1024 * 3, data=bytes(640 * 1024 * 3))
    image_every = max(small_count // max(images, 1), 1)
    base = 1_700_000_000
    k = 0
    for i in range(small_count):
        secs, ms = divmod(i, 1000)
        w.write(cs, base + secs, ms * 1_000_000, serialize_payload(String(data=f"message number {i}")))
        if i % image_every == 0 and k < images:
            img.header.seq = k
            img.header.stamp.secs = base + secs
            w.write(ci, base + secs, ms * 1_000_000 + 1, serialize_payload(img))
            k += 1
    w.close()
    tmp.rename(path)
    print(f"  {path.stat().st_size / 2**30:.2f} GiB in {time.perf_counter() - t0:.1f} s")
    return path


def warm_cache(path: Path) -> None:
    """Read the bag once so that neither reader pays the disk (whichever ran first would)."""
    with open(path, "rb", buffering=0) as f:
        while f.read(64 << 20):
            pass


def timed(cmd: list[str], repeat: int = 1) -> tuple[float, str]:
    best = float("inf")
    out = ""
    for _ in range(repeat):
        t0 = time.perf_counter()
        res = subprocess.run(cmd, capture_output=True, text=True)
        dt = time.perf_counter() - t0
        if res.returncode != 0:
            raise RuntimeError(f"{cmd} failed: {res.stderr[-2000:]}")
        best = min(best, dt)
        out = res.stdout
    return best, out


def bag_counts(path: Path) -> dict[str, int]:
    import rosbag

    with rosbag.Bag(path) as bag:
        info = bag.get_type_and_topic_info()
        return {topic: t.message_count for topic, t in info.topics.items()}


def record_run(recorder: list[str], out: Path, seconds: float, env: dict[str, str]) -> tuple[int, int, dict[str, int]]:
    rec = subprocess.Popen([*recorder, "-O", str(out), "/small", "/image"], env=env, stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL, cwd=out.parent)
    try:
        time.sleep(1.0)
        pub = subprocess.run([sys.executable, "-c", PUBLISHER, str(seconds)], env=env, capture_output=True, text=True,
                             timeout=seconds + 60)
        n_small, n_img = (int(x) for x in pub.stdout.split())
    finally:
        os.kill(rec.pid, signal.SIGINT)
        try:
            rec.wait(60)
        except subprocess.TimeoutExpired:
            os.kill(rec.pid, signal.SIGKILL)
            rec.wait()
    return n_small, n_img, bag_counts(out)


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--small-count", type=int, default=None, help="default 1,000,000 (100,000 with --play-only)")
    ap.add_argument("--images", type=int, default=None, help="default 1000 (100 with --play-only)")
    ap.add_argument("--record-seconds", type=float, default=10.0)
    ap.add_argument("--skip-debian-read", action="store_true")
    ap.add_argument("--busy", type=int, default=0, help="busy-loop processes running during the record runs")
    ap.add_argument("--play-only", action="store_true",
                    help="only `rosbag play -i` of a 100k small + 100 image bag to one subscriber, best of 3")
    args = ap.parse_args()
    compile_kame()
    if args.play_only:
        return play_only(args.small_count or 100_000, args.images or 100)
    bag = make_bag(args.small_count or 1_000_000, args.images or 1000)
    rows = []
    warm_cache(bag)
    k_info, _ = timed([str(BIN / "rosbag"), "info", str(bag)], 5)
    d_info, _ = timed([SYSTEM_PYTHON, "/usr/bin/rosbag", "info", str(bag)], 5)
    rows.append(("rosbag info", k_info, d_info))
    print(f"info: kame {k_info:.3f} s, Debian {d_info:.3f} s", flush=True)
    warm_cache(bag)
    k_read, k_n = timed([sys.executable, "-c", READ, str(bag)], 2)
    print(f"read: kame {k_read:.1f} s ({k_n.strip()} msgs)", flush=True)
    if not args.skip_debian_read:
        warm_cache(bag)
        d_read, d_n = timed([SYSTEM_PYTHON, "-c", READ, str(bag)], 2)
        print(f"read: Debian {d_read:.1f} s ({d_n.strip()} msgs)", flush=True)
        rows.append(("full read (deserialize all)", k_read, d_read))

    sys.path.insert(0, str(REPO))
    from tests.support import free_port, ros_env

    port = free_port()
    home = cache_dir() / "home"
    env = ros_env(home, f"http://127.0.0.1:{port}/")
    core = subprocess.Popen([str(BIN / "roscore"), "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    rec_rows = []
    busy: list[subprocess.Popen[bytes]] = []
    try:
        time.sleep(2.0)
        busy = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(args.busy)]
        with tempfile.TemporaryDirectory() as d:
            for name, cmd in (("kame", [str(BIN / "rosbag"), "record"]), ("Debian C++", ["/usr/lib/rosbag/record"])):
                if name.startswith("Debian") and not os.path.exists(cmd[0]):
                    continue
                out = Path(d) / f"rec_{name.split()[0]}.bag"
                n_small, n_img, got = record_run(cmd, out, args.record_seconds, env)
                rec_rows.append((name, n_small, got.get("/small", 0), n_img, got.get("/image", 0)))
                print(f"record {name}: small {got.get('/small', 0)}/{n_small}, images {got.get('/image', 0)}/{n_img}",
                      flush=True)
    finally:
        for p in busy:
            os.kill(p.pid, signal.SIGKILL)
            p.wait()
        os.kill(core.pid, signal.SIGINT)
        core.wait(20)

    print("\n| measure | kame | Debian rosbag | speed-up |\n|---|---|---|---|")
    for label, k, dbt in rows:
        print(f"| {label} ({bag.stat().st_size / 2**30:.2f} GiB) | {k:.3f} s | {dbt:.3f} s | {dbt / k:.1f}x |")
    load = f", {args.busy} busy loops" if args.busy else ""
    print(f"\n| recorder (1 kHz small + 30 Hz 6 MB{load}) | small got/published | images got/published |")
    print("|---|---|---|")
    for name, ns, gs, ni, gi in rec_rows:
        print(f"| {name} | {gs}/{ns} | {gi}/{ni} |")
    return 0


def play_only(small_count: int, images: int) -> int:
    bag = make_bag(small_count, images)
    sys.path.insert(0, str(REPO))
    from tests.support import free_port, ros_env

    port = free_port()
    env = ros_env(cache_dir() / "home", f"http://127.0.0.1:{port}/")
    core = subprocess.Popen([str(BIN / "roscore"), "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    runs = []
    try:
        time.sleep(2.0)
        for _ in range(3):
            warm_cache(bag)
            runs.append(play_run(bag, env))
            print("play: %.2f s wall, %.2f s CPU, %d msgs / %.0f MB received" % (
                runs[-1][0], runs[-1][1], runs[-1][2], runs[-1][3] / 1e6), flush=True)
    finally:
        os.kill(core.pid, signal.SIGINT)
        core.wait(20)
    wall, cpu, n, size = min(runs)
    size_mib = bag.stat().st_size / 2**20
    print(f"\n| rosbag play -i ({size_mib:.0f} MiB, {small_count} small + {images} images) | player wall | player CPU "
          "| received |\n|---|---|---|---|")
    print(f"| kame | {wall:.2f} s | {cpu:.2f} s | {n} msgs, {size / 1e6:.0f} MB |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
