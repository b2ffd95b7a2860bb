"""rviz's frame cost (issue 18): a 300k-point PointCloud2 at 10 Hz, a 2,000-marker
MarkerArray, a 2,000x2,000 map, each alone in a 1280x720 view, software-rendered (Mesa on a
private Xvfb when no DISPLAY is set). A frame is what the window does each turn: decode the
newest message (when one came), rebuild the scene, draw it and wait for GL to finish
(paintGL into the view's frame buffer + glFinish). Reported: frames per second the window can sustain (1 / mean frame
time), CPU per frame, and message-to-pixels latency (decode + build + draw of a frame with a
new message); and where a frame's CPU goes (median ms of the process, llvmpipe's threads
included): decoding the message, building the scene from it, painting a frame with a new message
(uploads + draw + glFinish) and one without (draw + glFinish). Each window has drawn two
empty frames, untimed, before its first message, as a running rviz has.

    .venv/bin/python bench/rviz_bench.py [--frames 60]
"""

from __future__ import annotations

import argparse
import gc
import os
import shutil
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from typing import Any

import numpy as np


def serialized(message: Any) -> bytes:
    from kame.node.topics import serialize_frame

    return b"".join(bytes(part) for part in serialize_frame(message))[4:]


def cloud(points: int) -> Any:
    from sensor_msgs.msg import PointCloud2, PointField

    rng = np.random.default_rng(1)
    xyz = rng.uniform(-5, 5, (points, 3)).astype(np.float32)
    message = PointCloud2(height=1, width=points, point_step=12, row_step=12 * points, data=xyz.tobytes(),
                          fields=[PointField(name=n, offset=4 * i, datatype=7, count=1) for i, n in enumerate("xyz")])
    message.header.frame_id = "map"
    return message


def marker_array(count: int) -> Any:
    from visualization_msgs.msg import Marker, MarkerArray

    markers = []
    for i in range(count):
        marker = Marker(ns="bench", id=i, type=(Marker.CUBE, Marker.SPHERE, Marker.ARROW, Marker.CYLINDER)[i % 4])
        marker.header.frame_id = "map"
        marker.pose.position.x, marker.pose.position.y = (i % 50) * 0.2 - 5, (i // 50) * 0.2 - 4
        marker.pose.orientation.w = 1.0
        marker.scale.x = marker.scale.y = marker.scale.z = 0.1
        marker.color.g = marker.color.a = 1.0
        markers.append(marker)
    return MarkerArray(markers=markers)


def grid_map(side: int) -> Any:
    from nav_msgs.msg import OccupancyGrid

    rng = np.random.default_rng(2)
    # numpy data, as kame's map_server, gmapping and costmaps publish it (a tuple of 4 million ints takes 60 ms to pack)
    grid = OccupancyGrid(data=rng.choice([-1, 0, 100], side * side).astype(np.int8))
    grid.header.frame_id = "map"
    grid.info.width = grid.info.height = side
    grid.info.resolution = 0.05
    grid.info.origin.position.x = grid.info.origin.position.y = -side * 0.025
    grid.info.origin.orientation.w = 1.0
    return grid


class Frames:
    fixed_frame = "map"

    def transform(self, frame_id: str) -> np.ndarray | str:
        return np.eye(4)

    def names(self) -> list[str]:
        return ["map"]

    def parent(self, frame_id: str) -> str | None:
        return None


def run(name: str, display: Any, cls: type[Any], payload: bytes, new_every: int, frames: int) -> str:
    from kame.rviz import config
    from kame.rviz.source import decode
    from kame.rviz.window import RvizWindow
    from OpenGL import GL
    from PySide6.QtTest import QTest
    from PySide6.QtWidgets import QApplication

    QApplication.instance() or QApplication(["bench"])
    window = RvizWindow(config.Config(displays=[display]), None)
    window.timer.stop()
    window.view_widget.setFixedSize(1280, 720)
    window.show()
    # a window not yet exposed paints nothing: frames timed before that measure no drawing at all
    if not QTest.qWaitForWindowExposed(window, 10_000):
        raise SystemExit("the window was never exposed")
    # a running rviz has drawn its empty scene many times before a message comes: two untimed
    # frames first, so the window's first GL paint (context set-up, shader compiles in llvmpipe)
    # is not counted as a message's latency
    for _ in range(2):
        window.draw(0.0, Frames())
        window.view.makeCurrent()
        window.view.paintGL()
        GL.glFinish()
        window.view.doneCurrent()
    gc.collect()  # as rviz's main does once its window is up (and the last scene's window is gone)
    gc.freeze()
    times, cpus, latencies = [], [], []
    phases: dict[str, list[float]] = {"decode": [], "build": [], "paint new": [], "paint same": []}
    for frame in range(frames):
        start, cpu = time.perf_counter(), time.process_time()
        if frame % new_every == 0:
            display.receive([decode(cls, payload)], 0.0)  # as rviz's source decodes it
            phases["decode"].append(time.process_time() - cpu)
        built = time.process_time()
        window.draw(0.0, Frames())
        painted = time.process_time()
        if frame % new_every == 0:  # a frame without one reuses the display's scene
            phases["build"].append(painted - built)
        # paintGL into the view's frame buffer, as Qt calls it, then wait for GL to finish: a
        # repaint() request may be dropped (it painted 2 frames of 30 on a busy machine), this may not
        window.view.makeCurrent()
        window.view.paintGL()
        GL.glFinish()
        window.view.doneCurrent()
        phases["paint new" if frame % new_every == 0 else "paint same"].append(time.process_time() - painted)
        elapsed = time.perf_counter() - start
        times.append(elapsed)
        cpus.append(time.process_time() - cpu)
        if frame % new_every == 0:
            latencies.append(elapsed)
    window.close()
    steady = times[1:]  # the first frame uploads the map and warms caches
    split = " | ".join(f"{1000 * np.median(phases[key]):.1f}" if phases[key] else "-"
                       for key in ("decode", "build", "paint new", "paint same"))
    return (f"| {name} | {1 / np.mean(steady):.1f} | {1000 * np.mean(cpus[1:]):.1f} | "
            f"{1000 * np.median(latencies):.0f} | {1000 * max(latencies):.0f} | {split} |")


def with_display(main: Callable[[], int]) -> int:
    if os.environ.get("DISPLAY") or shutil.which("Xvfb") is None:
        return main()
    read, write = os.pipe()
    server = subprocess.Popen(["Xvfb", "-displayfd", str(write), "-screen", "0", "1920x1080x24", "-nolisten", "tcp",
                               "-noreset"],
                              pass_fds=(write,), stderr=subprocess.DEVNULL)
    os.close(write)
    try:
        with os.fdopen(read) as pipe:
            display = ":" + pipe.readline().strip()
        # the bench runs in a child that ends, Qt application and all, before the X server does
        # (a QApplication outliving its server ends the process with an X I/O error)
        return subprocess.run([sys.executable, *sys.argv], env={**os.environ, "DISPLAY": display}).returncode
    finally:
        os.kill(server.pid, signal.SIGTERM)
        server.wait()


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=60)
    options = parser.parse_args()
    from kame.rviz import displays, markers
    from nav_msgs.msg import OccupancyGrid
    from sensor_msgs.msg import PointCloud2
    from visualization_msgs.msg import MarkerArray

    print("| scene | frames/s | CPU ms/frame | latency median ms | latency max ms | CPU ms: decode | build | "
          "paint new | paint same |")
    print("|---|---|---|---|---|---|---|---|---|")
    print(run("PointCloud2 300k points, new every 3rd frame (10 Hz at 30 fps)", displays.PointCloud2(),
              PointCloud2, serialized(cloud(300_000)), 3, options.frames), flush=True)
    print(run("MarkerArray 2,000 markers, one message", markers.MarkerArray(), MarkerArray,
              serialized(marker_array(2000)), options.frames, options.frames), flush=True)
    print(run("MarkerArray 2,000 markers, new every 10th frame (3 Hz at 30 fps)", markers.MarkerArray(), MarkerArray,
              serialized(marker_array(2000)), 10, options.frames), flush=True)
    print(run("Map 2,000x2,000, one message", displays.OccupancyGrid(), OccupancyGrid,
              serialized(grid_map(2000)), options.frames, options.frames), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(with_display(main))
