"""turtlesim left running: the demo (master, turtlesim with its window, draw_square) for N minutes,
with turtlesim's memory and time per frame at minute 1 and minute N (and every minute between).

    .venv/bin/python bench/turtlesim_soak.py [--minutes 30] [--offscreen]

The window is on a private Xvfb (`-displayfd`, stopped by its PID) when Xvfb is installed,
else on Qt's offscreen platform. turtlesim runs in this script's child (`--turtlesim`, its
steps timed) and its window process in a grandchild (`--window`, its paintEvent timed); each
prints one line of figures a minute, and this side adds both processes' resident memory
(VmRSS from /proc). Every process is stopped by its PID.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import threading
import time
from pathlib import Path

from bench_procs import free_port, stop

REPO = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
STATS = "soak-stats "


def rss_kib(pid: int) -> int:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1])
    return 0


def start_xvfb() -> tuple[subprocess.Popen[bytes], str]:
    read, write = os.pipe()
    xvfb = subprocess.Popen(["Xvfb", "-displayfd", str(write), "-screen", "0", "1024x768x24", "-nolisten", "tcp",
                             "-noreset"],
                            pass_fds=(write,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write)
    with os.fdopen(read) as pipe:
        number = pipe.readline().strip()
    if not number:
        stop(xvfb)
        raise RuntimeError("Xvfb did not start")
    return xvfb, f":{number}"


class MinuteFigures:
    """Durations collected over a minute, printed as one JSON line when the minute is up."""

    def __init__(self, who: str, keys: tuple[str, ...]) -> None:
        self.who = who
        self.samples: dict[str, list[float]] = {key: [] for key in keys}
        self.started = time.monotonic()
        self.next_report = self.started + 60.0

    def add(self, key: str, seconds: float) -> None:
        self.samples[key].append(seconds)
        now = time.monotonic()
        if now < self.next_report:
            return
        figures: dict[str, object] = {"who": self.who, "pid": os.getpid(),
                                      "minute": round((now - self.started) / 60.0)}
        for name, values in self.samples.items():
            values.sort()
            figures[f"{name}_n"] = len(values)
            figures[f"{name}_ms_mean"] = 1000 * sum(values) / max(len(values), 1)
            figures[f"{name}_ms_p99"] = 1000 * values[int(0.99 * (len(values) - 1))] if values else 0.0
            values.clear()
        print(STATS + json.dumps(figures), flush=True)
        self.next_report += 60.0


def window_child() -> int:
    """turtlesim's window process, its paintEvent timed."""
    from kame.turtlesim import gui

    figures = MinuteFigures("window", ("paint",))
    paint_event = gui.TurtleWindow.paintEvent

    def timed_paint(self: gui.TurtleWindow, event: object) -> None:
        t0 = time.perf_counter()
        paint_event(self, event)  # type: ignore[arg-type]
        figures.add("paint", time.perf_counter() - t0)

    gui.TurtleWindow.paintEvent = timed_paint  # type: ignore[method-assign]
    from kame.msg.catalog import SHARE_DIR

    return gui.main(["--window", "TurtleSim", str(SHARE_DIR / "turtlesim" / "images")])


def turtlesim_child() -> int:
    """turtlesim_node, its steps timed (frame(): step, publish, snapshot), its window the timed one."""
    from kame.turtlesim import node

    figures = MinuteFigures("sim", ("step", "interval"))
    frame = node.TurtlesimNode.frame
    last = [0.0]

    def timed_frame(self: node.TurtlesimNode) -> object:
        t0 = time.perf_counter()
        if last[0]:
            figures.add("interval", t0 - last[0])
        last[0] = t0
        result = frame(self)
        figures.add("step", time.perf_counter() - t0)
        return result

    node.TurtlesimNode.frame = timed_frame  # type: ignore[method-assign,assignment]
    node.window_command = lambda: [sys.executable, __file__, "--window"]
    return node.main(["turtlesim_node"])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--minutes", type=int, default=30)
    parser.add_argument("--offscreen", action="store_true", help="Qt's offscreen platform even if Xvfb is there")
    parser.add_argument("--turtlesim", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--window", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.turtlesim:
        return turtlesim_child()
    if args.window:
        return window_child()
    sys.path.insert(0, str(REPO / "bench"))
    from kame_bytecode import compile_kame

    compile_kame()
    port = free_port()
    home = Path(os.environ.get("TMPDIR", "/tmp")) / f"kame-soak-{os.getpid()}"
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
    env.update(ROS_MASTER_URI=f"http://127.0.0.1:{port}/", ROS_HOSTNAME="127.0.0.1", ROS_HOME=str(home),
               PYTHONUNBUFFERED="1")
    env.pop("DISPLAY", None)
    procs: list[subprocess.Popen[bytes] | subprocess.Popen[str]] = []
    try:
        if shutil.which("Xvfb") and not args.offscreen:
            xvfb, display = start_xvfb()
            procs.append(xvfb)
            env["DISPLAY"] = display
            where = f"Xvfb {display}"
        else:
            env["QT_QPA_PLATFORM"] = "offscreen"
            where = "Qt offscreen"
        procs.append(subprocess.Popen([str(BIN / "rosmaster"), "--core", "-p", str(port)], env=env,
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        sim = subprocess.Popen([sys.executable, __file__, "--turtlesim"], env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True)
        procs.append(sim)
        procs.append(subprocess.Popen([str(BIN / "rosrun"), "turtlesim", "draw_square"], env=env,
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        rows: list[dict[str, float]] = []
        halves: dict[int, dict[str, float]] = {}
        done = threading.Event()

        def read() -> None:
            assert sim.stdout is not None
            for line in sim.stdout:
                if line.startswith(STATS):
                    half = json.loads(line[len(STATS):])
                    row = halves.setdefault(half["minute"], {})
                    row.update({k: v for k, v in half.items() if k not in ("who", "pid")})
                    row[f"{half['who']}_rss_mib"] = rss_kib(half["pid"]) / 1024
                    if "sim_rss_mib" in row and "window_rss_mib" in row:
                        row["load1"] = os.getloadavg()[0]
                        rows.append(halves.pop(half["minute"]))
                        print(format_row(row), file=sys.stderr, flush=True)
                        if row["minute"] >= args.minutes:
                            done.set()
                elif "without a window" in line or "failed" in line or "Error" in line:
                    print("turtlesim: " + line.rstrip(), file=sys.stderr, flush=True)
            done.set()

        reader = threading.Thread(target=read)
        reader.start()
        print(f"turtlesim soak: {args.minutes} min on {where}; one line a minute", file=sys.stderr, flush=True)
        done.wait()
        stop(sim)
        reader.join()
    finally:
        for proc in reversed(procs):
            stop(proc)
        shutil.rmtree(home, ignore_errors=True)
    if not rows:
        print("turtlesim soak: turtlesim ended before its first minute", file=sys.stderr)
        return 1
    print(f"turtlesim soak, {where}, {len(rows)} min (load average at each minute in the last column)")
    print(HEADER)
    for row in (rows[0], rows[-1]):
        print(format_row(row))
    return 0 if rows[-1]["minute"] >= args.minutes else 1


HEADER = ("minute  sim RSS MiB  window RSS MiB  frames  paint ms mean/p99  step ms mean/p99  "
          "interval ms mean/p99  load1")


def format_row(row: dict[str, float]) -> str:
    return (f"{row['minute']:6.0f}  {row['sim_rss_mib']:11.1f}  {row['window_rss_mib']:14.1f}  "
            f"{row['paint_n']:6.0f}  {row['paint_ms_mean']:8.2f} / {row['paint_ms_p99']:5.2f}  "
            f"{row['step_ms_mean']:7.2f} / {row['step_ms_p99']:5.2f}  "
            f"{row['interval_ms_mean']:11.2f} / {row['interval_ms_p99']:5.2f}  {row['load1']:5.2f}")


if __name__ == "__main__":
    sys.exit(main())
