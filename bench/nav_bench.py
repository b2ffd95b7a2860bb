"""The navigation stack's CPU per node at the TurtleBot's rates, on the simulated TurtleBot.

    .venv/bin/python bench/nav_bench.py [--seconds 60]

stageros in the office world (real time, laser at 10 Hz as a TurtleBot's), and turtlebot_gazebo's
amcl_demo.launch (map_server, amcl and move_base with turtlebot_navigation's parameters), with a
kame master. Once amcl publishes, goals across the office are sent on /move_base_simple/goal every
--goal-period seconds, back and forth, so that the robot drives (amcl filters, move_base plans and
controls) for --seconds; each node's CPU time (user + system, from /proc) over that window,
divided by the wall time, is its share of one core. Target: amcl + move_base (+ SLAM, measured
apart) together under one core.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

from bench_procs import cpu_seconds, free_port, stop

REPO = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
OFFICE = REPO / "src" / "kame" / "share" / "turtlebot_gazebo" / "worlds" / "office.yaml"
GOALS = [(2.0, -3.0), (-2.0, 3.0), (-6.0, 0.2), (0.0, 0.0)]


def descendants(root: int) -> dict[int, str]:
    """pid -> command line of every process under `root` (ours only: found from its children)."""
    parents: dict[int, int] = {}
    lines: dict[int, str] = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                parents[int(entry)] = int(f.read().rsplit(")", 1)[1].split()[1])
            with open(f"/proc/{entry}/cmdline", "rb") as f:
                lines[int(entry)] = f.read().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
    found: dict[int, str] = {}
    frontier = [root]
    while frontier:
        parent = frontier.pop()
        for pid, ppid in parents.items():
            if ppid == parent and pid not in found:
                found[pid] = lines.get(pid, "")
                frontier.append(pid)
    return found


def node_pid(root: int, name: str) -> int:
    for pid, line in descendants(root).items():
        if f"__name:={name}" in line:
            return pid
    raise RuntimeError(f"no {name} node under process {root}")


def wait_for(env: dict[str, str], topic: str) -> None:
    subprocess.run([str(BIN / "rostopic"), "echo", "-n", "1", "--noarr", topic], env=env, capture_output=True,
                   timeout=120, check=True)


def robot_at(env: dict[str, str]) -> str:
    out = subprocess.run([str(BIN / "rostopic"), "echo", "-n", "1", "/base_pose_ground_truth/pose/pose/position"],
                         env=env, capture_output=True, text=True, timeout=60, check=True).stdout
    values = dict(line.split(": ") for line in out.splitlines() if ": " in line)
    return f"({float(values['x']):.2f}, {float(values['y']):.2f})"


def send_goal(env: dict[str, str], x: float, y: float) -> None:
    pose = f"{{header: {{frame_id: map}}, pose: {{position: {{x: {x}, y: {y}}}, orientation: {{w: 1.0}}}}}}"
    subprocess.run([str(BIN / "rostopic"), "pub", "-1", "/move_base_simple/goal", "geometry_msgs/PoseStamped", pose],
                   env=env, capture_output=True, timeout=60, check=True)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--goal-period", type=float, default=20.0)
    parser.add_argument("--home", type=Path, default=Path("/tmp/kame-nav-bench"))
    args = parser.parse_args()
    args.home.mkdir(parents=True, exist_ok=True)
    port = free_port()
    env = {**os.environ, "ROS_MASTER_URI": f"http://127.0.0.1:{port}/", "ROS_HOSTNAME": "127.0.0.1",
           "ROS_HOME": str(args.home)}
    procs: list[subprocess.Popen[str]] = []

    def start(*command: str) -> subprocess.Popen[str]:
        proc = subprocess.Popen(list(command), env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, text=True)
        procs.append(proc)
        return proc

    try:
        start(str(BIN / "rosmaster"), "--core", "-p", str(port))
        for _ in range(100):
            if subprocess.run([str(BIN / "rosparam"), "set", "/use_sim_time", "true"], env=env,
                              capture_output=True).returncode == 0:
                break
            time.sleep(0.1)
        stage = start(str(BIN / "rosrun"), "stage_ros", "stageros", "-g", str(OFFICE), "base_scan:=scan",
                      "_laser_rate:=10", "_extra_cmd_vel_topics:=[cmd_vel_mux/input/navi]")
        demo = start(str(BIN / "roslaunch"), "turtlebot_gazebo", "amcl_demo.launch", f"map_file:={OFFICE}")
        wait_for(env, "/amcl_pose")
        nodes = {"amcl": node_pid(demo.pid, "amcl"), "move_base": node_pid(demo.pid, "move_base"),
                 "stageros": stage.pid}
        before = {name: cpu_seconds(pid) for name, pid in nodes.items()}
        started = time.monotonic()
        goal = 0
        visited = []
        while time.monotonic() - started < args.seconds:
            visited.append(robot_at(env))
            send_goal(env, *GOALS[goal % len(GOALS)])
            goal += 1
            time.sleep(max(0.0, min(args.goal_period, args.seconds - (time.monotonic() - started))))
        wall = time.monotonic() - started
        used = {name: cpu_seconds(pid) - before[name] for name, pid in nodes.items()}
        load = os.getloadavg()
        visited.append(robot_at(env))
        print("the robot (ground truth) at each goal's sending and at the end:", " ".join(visited))
        print(f"{wall:.0f} s of driving ({goal} goals), load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
        print("| node | CPU s | share of one core |")
        print("| --- | ---: | ---: |")
        for name, seconds in used.items():
            print(f"| {name} | {seconds:.1f} | {100 * seconds / wall:.0f}% |")
        together = used["amcl"] + used["move_base"]
        print(f"| amcl + move_base | {together:.1f} | {100 * together / wall:.0f}% |")
    finally:
        for proc in reversed(procs):
            stop(proc, grace=15)
    return 0


if __name__ == "__main__":
    sys.exit(main())
