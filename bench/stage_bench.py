"""kame's 2-D robot world: simulated seconds per wall second, the world alone and stageros whole.

    .venv/bin/python bench/stage_bench.py [--seconds 5] [--beams 720]

world: kame.stage.world.World on the playground map stepped at stageros's 0.01 s with every
robot's laser (360 degrees, --beams beams, 10 m) cast every fifth step (20 Hz), for 1 and 10
robots. node: stageros at ~real_time_factor 0 (as fast as it can) with the same lasers and
robots, publishing everything (odom, ground truth, tf at 50 Hz, scans at 20 Hz, /clock each
step), with a kame master; its /clock is read twice, --seconds apart. Targets: >= 10x real time
for one robot, >= 1x for ten.
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import time
from pathlib import Path

from bench_procs import free_port, stop

REPO = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
PLAYGROUND = REPO / "src" / "kame" / "share" / "turtlebot_gazebo" / "worlds" / "playground.yaml"
STEP, SCAN_EVERY = 0.01, 5


def placements(count: int) -> list[tuple[str, float, float]]:
    """Robots on a ring of radius 1.2 m around the playground's centre (open ground)."""
    return [(f"robot_{i}", 1.2 * math.cos(2 * math.pi * i / count), 1.2 * math.sin(2 * math.pi * i / count))
            for i in range(count)]


def world_rate(count: int, beams: int, seconds: float) -> float:
    from kame.stage.mapfile import load, parse_description
    from kame.stage.world import LaserModel, Walls, World

    description = parse_description(PLAYGROUND.read_text())
    image = Path(description.image_path(str(PLAYGROUND)))
    laser = LaserModel(beams=beams, angle_min=-math.pi, angle_max=math.pi, range_min=0.12, range_max=10.0)
    world = World(Walls(load(description, image.read_bytes(), str(image))), laser=laser)
    for name, x, y in placements(count):
        world.spawn(name, x, y, 0.0)
    steps = 0
    start = time.perf_counter()
    while time.perf_counter() - start < seconds:
        for name in world.names():
            world.command(name, 0.3, 0.4)
        world.step(STEP)
        steps += 1
        if steps % SCAN_EVERY == 0:
            world.scans()
    return steps * STEP / (time.perf_counter() - start)


def clock(env: dict[str, str]) -> float:
    out = subprocess.run([str(BIN / "rostopic"), "echo", "-n", "1", "/clock"], env=env, capture_output=True,
                         text=True, timeout=30, check=True).stdout
    secs = int(out.split("secs:")[1].split()[0])
    nsecs = int(out.split("nsecs:")[1].split()[0])
    return secs + nsecs / 1e9


def node_rate(count: int, beams: int, seconds: float, home: Path) -> float:
    port = free_port()
    env = {**os.environ, "ROS_MASTER_URI": f"http://127.0.0.1:{port}/", "ROS_HOSTNAME": "127.0.0.1",
           "ROS_HOME": str(home)}
    master = subprocess.Popen([str(BIN / "rosmaster"), "--core", "-p", str(port)], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, text=True)
    sim = None
    try:
        robots = "[" + ", ".join(f"{{name: {n}, x: {x:.3f}, y: {y:.3f}}}" for n, x, y in placements(count)) + "]"
        for _ in range(100):
            if subprocess.run([str(BIN / "rosparam"), "set", "/stageros/robots", robots], env=env,
                              capture_output=True).returncode == 0:
                break
            time.sleep(0.1)
        sim = subprocess.Popen([str(BIN / "rosrun"), "stage_ros", "stageros", str(PLAYGROUND),
                                "_real_time_factor:=0", f"_laser_beams:={beams}", "_laser_angle_min:=-3.14159",
                                "_laser_angle_max:=3.14159", "_laser_range_min:=0.12"],
                               env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, text=True)
        first, wall_first = clock(env), time.perf_counter()
        time.sleep(seconds)
        last, wall_last = clock(env), time.perf_counter()
        return (last - first) / (wall_last - wall_first)
    finally:
        if sim is not None:
            stop(sim)
        stop(master)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=5.0)
    parser.add_argument("--beams", type=int, default=720)
    parser.add_argument("--home", type=Path, default=Path("/tmp/kame-stage-bench"))
    args = parser.parse_args()
    args.home.mkdir(parents=True, exist_ok=True)
    print(f"| robots | world alone (x real time) | stageros (x real time) |   ({args.beams}-beam lasers at 20 Hz)")
    print("| ---: | ---: | ---: |")
    for count in (1, 10):
        world = world_rate(count, args.beams, args.seconds)
        node = node_rate(count, args.beams, args.seconds, args.home)
        print(f"| {count} | {world:.1f} | {node:.1f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
