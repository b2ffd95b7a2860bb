"""The camera lesson's figures (issue 33): usb_cam's test pattern at 1920x1080 in yuyv, converted
to rgb8 at 30 fps, with one subscriber: usb_cam's CPU share of one core (target <= 50 %), the
rate the subscriber gets, and the latency from the frame's stamp (taken once it is converted,
as usb_cam's grab_image stamps it) to the subscriber's callback; then image_proc's rectify at
1080p: frames a second of the rectification itself (target >= 30) and of the image_proc node
end to end (usb_cam testsrc 1080p with a calibration -> image_proc -> a subscriber to
image_rect_color); and from the stamp to rviz's Camera display on the screen (rviz's
KAME_RVIZ_STATS: the 3-D view's buffer swap of the frame that took the image; the image
panel is painted in the same turn of the window's loop), on a private Xvfb when no DISPLAY is set.

CPU from /proc (user + system) over --seconds, after a second of warm-up; the load average is
printed beside. Run: .venv/bin/python bench/camera_bench.py
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import textwrap
import time
import xmlrpc.client
from pathlib import Path
from typing import Any

from bench_procs import cpu_seconds, free_port, stop
from kame_bytecode import compile_kame
from rviz_bench import with_display

REPO = Path(__file__).resolve().parents[1]
BIN = REPO / ".venv" / "bin"
WIDTH, HEIGHT = 1920, 1080

SUBSCRIBER = textwrap.dedent("""
    import json, sys, threading, time
    import rospy
    from sensor_msgs.msg import Image
    topic, seconds = sys.argv[1], float(sys.argv[2])
    latencies, arrivals = [], []
    done = threading.Event()
    def take(image):
        now = time.time()
        arrivals.append(now)
        latencies.append(now - image.header.stamp.to_sec())
    rospy.init_node("camera_bench_sub", anonymous=True)
    rospy.Subscriber(topic, Image, take, queue_size=1)
    rospy.on_shutdown(done.set)
    while not arrivals and not done.wait(0.05):
        pass
    time.sleep(1.0)  # warm-up
    start = len(arrivals)
    print("measuring", flush=True)
    done.wait(seconds)
    got = arrivals[start:]
    lat = sorted(latencies[start:])
    rate = (len(got) - 1) / (got[-1] - got[0]) if len(got) > 1 else 0.0
    print(json.dumps({"rate": rate, "frames": len(got), "lat_p50": lat[len(lat) // 2] if lat else None,
                      "lat_p90": lat[int(len(lat) * 0.9)] if lat else None}), flush=True)
""")


def environment(home: Path, uri: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_") and k != "PYTHONPATH"}
    env.update(ROS_MASTER_URI=uri, ROS_HOME=str(home), ROS_HOSTNAME="127.0.0.1", PYTHONUNBUFFERED="1")
    return env


def wait_for_master(uri: str) -> None:
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline:
        try:
            code, _, _ = xmlrpc.client.ServerProxy(uri).getPid("/bench")  # type: ignore[misc,str-unpack]
            if code == 1:
                return
        except OSError:
            time.sleep(0.1)
    raise RuntimeError("the master did not start")


def measure(env: dict[str, str], home: Path, topic: str, seconds: float, cpu_pids: dict[str, int]
            ) -> dict[str, Any]:
    sub = subprocess.Popen([str(BIN / "python"), "-c", SUBSCRIBER, topic, str(seconds)], env=env, cwd=home,
                           stdout=subprocess.PIPE, text=True)
    assert sub.stdout is not None
    assert sub.stdout.readline().strip() == "measuring"
    before = {name: cpu_seconds(pid) for name, pid in cpu_pids.items()}
    started = time.monotonic()
    result: dict[str, Any] = json.loads(sub.stdout.readline())
    elapsed = time.monotonic() - started
    for name, pid in cpu_pids.items():
        result[f"cpu_{name}"] = (cpu_seconds(pid) - before[name]) / elapsed
    stop(sub)
    return result


RVIZ_CONFIG = """Visualization Manager:
  Global Options:
    Fixed Frame: head_camera
    Frame Rate: 30
  Displays:
    - Class: rviz/Camera
      Name: Camera
      Enabled: true
      Image Topic: /usb_cam/image_raw
Window Geometry:
  Width: 1280
  Height: 800
"""


def rviz_latency(env: dict[str, str], home: Path, seconds: float) -> tuple[float, float, int]:
    """(p50, p90) seconds from usb_cam's stamp to rviz's frame showing the image in its Camera
    display (rviz's KAME_RVIZ_STATS), and how many frames it showed."""
    config, shown = home / "camera.rviz", home / "camera.shown"
    config.write_text(RVIZ_CONFIG)
    rviz = subprocess.Popen([str(BIN / "rviz"), "-d", str(config)], env={**env, "KAME_RVIZ_STATS": str(shown)},
                            cwd=home, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not (shown.exists() and shown.read_text().count("\n") > 30):
            time.sleep(0.2)  # rviz starting and warming up: no event to wait on from here
        start = shown.read_text().count("\n") if shown.exists() else 0
        time.sleep(seconds)
    finally:
        stop(rviz)
    rows = [line.split() for line in shown.read_text().splitlines()[start:]] if shown.exists() else []
    latencies = sorted(float(row[3]) - float(row[1]) for row in rows if row and row[0] == "/usb_cam/image_raw")
    if not latencies:
        return float("nan"), float("nan"), 0
    return latencies[len(latencies) // 2], latencies[int(len(latencies) * 0.9)], len(latencies)


def rectify_rate(frames: int) -> float:
    sys.path.insert(0, str(REPO / "src"))
    import numpy as np
    from kame.camera.image_processing import RectifyMaps
    from sensor_msgs.msg import CameraInfo

    info = calibrated_info()
    picture = np.random.default_rng(1).integers(0, 255, (HEIGHT, WIDTH, 3), np.uint8)
    maps = RectifyMaps()
    maps.rectify(picture, CameraInfo(**info))  # the maps, made once
    best = 0.0
    for _ in range(3):
        start = time.perf_counter()
        for _ in range(frames):
            maps.rectify(picture, CameraInfo(**info))
        best = max(best, frames / (time.perf_counter() - start))
    return best


def cv2_threads() -> int:
    import cv2

    return int(cv2.getNumThreads())


def calibrated_info() -> dict[str, Any]:
    fx, cx, cy = 1400.0, WIDTH / 2 - 0.5, HEIGHT / 2 - 0.5
    k = [fx, 0.0, cx, 0.0, fx, cy, 0.0, 0.0, 1.0]
    return {"width": WIDTH, "height": HEIGHT, "distortion_model": "plumb_bob", "K": k,
            "D": [-0.25, 0.08, 0.0, 0.0, 0.0], "R": [1.0, 0, 0, 0, 1.0, 0, 0, 0, 1.0],
            "P": [fx, 0.0, cx, 0.0, 0.0, fx, cy, 0.0, 0.0, 0.0, 1.0, 0.0]}


def calibration_yaml(path: Path) -> None:
    info = calibrated_info()
    lines = [f"image_width: {WIDTH}", f"image_height: {HEIGHT}", "camera_name: head_camera"]
    for key, name, rows, cols in (("K", "camera_matrix", 3, 3), ("D", "distortion_coefficients", 1, 5),
                                  ("R", "rectification_matrix", 3, 3), ("P", "projection_matrix", 3, 4)):
        lines += [f"{name}:", f"  rows: {rows}", f"  cols: {cols}", f"  data: {info[key]}"]
    path.write_text("\n".join(lines) + "\ndistortion_model: plumb_bob\n")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--frames", type=int, default=60, help="frames a round of the rectify timing")
    options = parser.parse_args()
    compile_kame()
    print(f"loadavg {' '.join(f'{x:.2f}' for x in os.getloadavg())}", file=sys.stderr)
    rows: list[tuple[str, str]] = []
    with tempfile.TemporaryDirectory() as folder:
        home = Path(folder)
        calibration_yaml(home / "head_camera.yaml")
        port = free_port()
        uri = f"http://127.0.0.1:{port}/"
        env = environment(home, uri)
        master = subprocess.Popen([str(BIN / "rosmaster"), "--core", "-p", str(port)], env=env,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        procs = [master]
        try:
            wait_for_master(uri)
            camera = subprocess.Popen([str(BIN / "rosrun"), "usb_cam", "usb_cam_node", "_video_device:=testsrc",
                                       "_pixel_format:=yuyv", f"_image_width:={WIDTH}", f"_image_height:={HEIGHT}",
                                       "_framerate:=30", f"_camera_info_url:=file://{home}/head_camera.yaml"],
                                      env=env, cwd=home, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            procs.append(camera)
            cam = measure(env, home, "/usb_cam/image_raw", options.seconds, {"usb_cam": camera.pid})
            rows += [("usb_cam testsrc 1920x1080 yuyv->rgb8 @30: CPU of one core", f"{cam['cpu_usb_cam']:.0%}"),
                     ("  rate at the subscriber", f"{cam['rate']:.1f} fps"),
                     ("  stamp -> subscriber callback p50 / p90",
                      f"{1000 * float(cam['lat_p50']):.1f} / {1000 * float(cam['lat_p90']):.1f} ms")]
            p50, p90, shown = rviz_latency(env, home, options.seconds)
            rows += [("rviz Camera display, 1080p: stamp -> frame swapped p50 / p90",
                      f"{1000 * p50:.1f} / {1000 * p90:.1f} ms ({shown / options.seconds:.1f} shown/s)")]
            proc_env = {**env, "ROS_NAMESPACE": "usb_cam"}
            image_proc = subprocess.Popen([str(BIN / "rosrun"), "image_proc", "image_proc"], env=proc_env, cwd=home,
                                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            procs.append(image_proc)
            rect = measure(env, home, "/usb_cam/image_rect_color", options.seconds,
                           {"usb_cam": camera.pid, "image_proc": image_proc.pid})
            rows += [("image_proc node 1080p rect_color: rate at the subscriber", f"{rect['rate']:.1f} fps"),
                     ("  image_proc CPU of one core", f"{rect['cpu_image_proc']:.0%}"),
                     ("  stamp -> subscriber callback p50 / p90",
                      f"{1000 * float(rect['lat_p50']):.1f} / {1000 * float(rect['lat_p90']):.1f} ms")]
        finally:
            for proc in reversed(procs):
                stop(proc)
    rows.append((f"rectify 1920x1080 rgb8 (the remap alone, OpenCV on {cv2_threads()} threads)",
                 f"{rectify_rate(options.frames):.0f} fps"))
    print(f"loadavg after {' '.join(f'{x:.2f}' for x in os.getloadavg())}", file=sys.stderr)
    width = max(len(name) for name, _ in rows)
    for name, value in rows:
        print(f"{name:<{width}}  {value}")
    return 0


if __name__ == "__main__":
    sys.exit(with_display(main))
