"""gmapping in kame: how often the office drive's map passes, and CPU of the navigation nodes.

    .venv/bin/python bench/slam_bench.py sweep [--seeds 4]
    .venv/bin/python bench/slam_bench.py nodes [--seconds 30]

sweep: tests/nav/test_slam.py's drive through the office (turtlebot_navigation's gmapping
values) for --seeds world seeds (the odometry's miscalibration) x 2 filter seeds, at stageros's
drift and three times it, with 30 and 80 particles; prints how many maps pass the test's metric
and the CPU time per processed scan and per scan (process time, in-process).
nodes: stageros in the office (turtlebot_world.launch's settings, its laser at 10 Hz, real time),
slam_gmapping and move_base (gmapping_demo.launch) plus map_server and amcl (its transform off,
gmapping's is the one used), while move_base drives the robot down the corridor and back; prints
each node's CPU use (user + system time of its process over --seconds of wall time, in percent
of one core). Target: SLAM + amcl + move_base under one core together.
"""

from __future__ import annotations

import argparse
import os
import signal
import statistics
import subprocess
import sys
import time
from pathlib import Path

from bench_procs import free_port

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))
BIN = Path(sys.executable).parent
OFFICE = REPO / "src" / "kame" / "share" / "turtlebot_gazebo" / "worlds" / "office.yaml"


def sweep(seeds: int) -> None:
    from kame.nav.slam import Gmapping
    from kame.stage.world import LaserModel, OdometryModel, Walls, World
    from tests.nav.mapscore import AGREEMENT, DRAWN_NEAR_WALLS, WALLS_DRAWN, score
    from tests.nav.test_amcl import OFFICE_DRIVE
    from tests.nav.test_slam import TURTLEBOT
    from tests.nav.worlds import load_world_map

    truth = load_world_map("office")
    print("| drift | particles | maps passing | agreement (median) | walls drawn near walls (min) | "
          "walls seen drawn (min) | CPU ms per processed scan | CPU ms per scan |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for label, drift in (("stageros's", OdometryModel()), ("3x", OdometryModel(0.03, 0.05))):
        for particles in (30, 80):
            params = type(TURTLEBOT)(**{**TURTLEBOT.__dict__, "particles": particles})
            passed, agreements, near, drawn, cpu, processed, scans = 0, [], [], [], 0.0, 0, 0
            for seed in range(1, seeds + 1):
                for filter_seed in (1, 2):
                    world = World(Walls(truth), laser=LaserModel(noise=0.01), odometry=drift, seed=seed)
                    world.spawn("bot", 0.0, 0.0, 0.0)
                    slam = Gmapping(params, seed=filter_seed)
                    for linear, angular, seconds in OFFICE_DRIVE:
                        for step in range(round(seconds / 0.05)):
                            world.command("bot", linear, angular)
                            world.step(0.05)
                            if step % 2:
                                odom = world.robot("bot").odom
                                ranges = world.scans(["bot"])["bot"]
                                start = time.process_time()
                                slam.add_scan((odom.x, odom.y, odom.theta), ranges, world.laser.angles(),
                                              world.laser.range_max)
                                cpu += time.process_time() - start
                                scans += 1
                    processed += slam.scans_processed
                    found = score(slam.occupancy(), truth)
                    agreements.append(found.agreement)
                    near.append(found.drawn_near_walls)
                    drawn.append(found.walls_drawn)
                    passed += (found.agreement >= AGREEMENT and found.drawn_near_walls >= DRAWN_NEAR_WALLS
                               and found.walls_drawn >= WALLS_DRAWN)
            print(f"| {label} | {particles} | {passed}/{2 * seeds} | {statistics.median(agreements):.3f} | "
                  f"{min(near):.3f} | {min(drawn):.3f} | {1000 * cpu / processed:.0f} | {1000 * cpu / scans:.1f} |",
                  flush=True)


def tree_cpu(pid: int) -> float:
    """User + system seconds of a process and its live descendants."""
    tick = os.sysconf("SC_CLK_TCK")
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            children.setdefault(int(fields[1]), []).append(int(entry.name))
    total, todo = 0.0, [pid]
    while todo:
        current = todo.pop()
        try:
            fields = Path(f"/proc/{current}/stat").read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        total += (int(fields[11]) + int(fields[12])) / tick
        todo.extend(children.get(current, []))
    return total


def robot_x(env: dict[str, str]) -> float:
    out = subprocess.run([str(BIN / "rostopic"), "echo", "-n", "1", "/base_pose_ground_truth/pose/pose/position/x"],
                         env=env, capture_output=True, text=True, timeout=30, check=True).stdout
    return float(out.split()[0])


def descendant(pid: int, word: str) -> int:
    """The first process below `pid` whose command line names `word`."""
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            command = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode()
            parent = int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
        except OSError:
            continue
        if word in command and parent == pid:
            return int(entry.name)
    raise LookupError(f"no process running {word} under {pid}")


def nodes(seconds: float, home: Path) -> None:
    port = free_port()
    env = {**os.environ, "ROS_MASTER_URI": f"http://127.0.0.1:{port}/", "ROS_HOSTNAME": "127.0.0.1",
           "ROS_HOME": str(home)}
    procs: dict[str, subprocess.Popen[str]] = {}

    def start(name: str, *args: str) -> None:
        procs[name] = subprocess.Popen([str(BIN / args[0]), *args[1:]], env=env, stdout=subprocess.DEVNULL,
                                       stderr=subprocess.DEVNULL, text=True)

    try:
        start("master", "rosmaster", "--core", "-p", str(port))
        time.sleep(1.0)
        subprocess.run([str(BIN / "rosparam"), "set", "/use_sim_time", "true"], env=env, check=True)
        # the TurtleBot's base also listens where turtlebot_navigation's move_base sends (cmd_vel_mux/input/navi)
        start("stageros", "rosrun", "stage_ros", "stageros", str(OFFICE), "base_scan:=scan", "_laser_rate:=10",
              "_extra_cmd_vel_topics:=[cmd_vel_mux/input/navi]")
        start("map_server", "rosrun", "map_server", "map_server", str(OFFICE), "map:=office_map",
              "static_map:=office_static_map")
        start("amcl", "rosrun", "amcl", "amcl", "_base_frame_id:=base_footprint", "_tf_broadcast:=false",
              "static_map:=office_static_map", "_min_particles:=500", "_max_particles:=2000",
              "_update_min_d:=0.25", "_update_min_a:=0.2", "_resample_interval:=1")
        start("gmapping_demo", "roslaunch", "turtlebot_navigation", "gmapping_demo.launch")
        time.sleep(15.0)  # everyone up, the first map out
        launched = procs.pop("gmapping_demo")
        pids = {name: p.pid for name, p in procs.items() if name != "master"}
        pids["slam_gmapping"] = descendant(launched.pid, "slam_gmapping")
        pids["move_base"] = descendant(launched.pid, "move_base")
        procs["gmapping_demo"] = launched
        goals = [("4.0", "0.0"), ("-4.0", "0.0")]
        goal_procs = []
        xs = [robot_x(env)]
        for x, y in goals:
            goal_procs.append(subprocess.Popen(
                [str(BIN / "rostopic"), "pub", "-1", "/move_base_simple/goal", "geometry_msgs/PoseStamped",
                 f"{{header: {{frame_id: map}}, pose: {{position: {{x: {x}, y: {y}}}, orientation: {{w: 1.0}}}}}}"],
                env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
            goal_procs[-1].wait(30)
            if (x, y) == goals[0]:
                before = {name: tree_cpu(pid) for name, pid in pids.items()}
                wall = time.perf_counter()
                time.sleep(seconds / 2)
                xs.append(robot_x(env))
        time.sleep(seconds / 2)
        xs.append(robot_x(env))
        elapsed = time.perf_counter() - wall
        after = {name: tree_cpu(pid) for name, pid in pids.items()}
        print(f"| node | CPU (% of one core) over {elapsed:.0f} s |")
        print("|---|---:|")
        for name in ("stageros", "slam_gmapping", "amcl", "move_base", "map_server"):
            print(f"| {name} | {100 * (after[name] - before[name]) / elapsed:.0f} |")
        navigation = sum(after[n] - before[n] for n in ("slam_gmapping", "amcl", "move_base"))
        print(f"| slam_gmapping + amcl + move_base | {100 * navigation / elapsed:.0f} |")
        print("the robot's x: " + " -> ".join(f"{x:.2f}" for x in xs))
    finally:
        for proc in reversed(list(procs.values())):
            if proc.poll() is None:
                proc.send_signal(signal.SIGINT)
                try:
                    proc.wait(15)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait()


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("what", choices=("sweep", "nodes"))
    parser.add_argument("--seeds", type=int, default=4)
    parser.add_argument("--seconds", type=float, default=30.0)
    parser.add_argument("--home", type=Path, default=Path("/tmp/kame-slam-bench"))
    args = parser.parse_args()
    if args.what == "sweep":
        sweep(args.seeds)
    else:
        args.home.mkdir(parents=True, exist_ok=True)
        nodes(args.seconds, args.home)
    return 0


if __name__ == "__main__":
    sys.exit(main())
