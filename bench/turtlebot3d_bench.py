"""The TurtleBot in 3-D as a user runs it: real-time factor of turtlebot_world.launch with every
sensor rendered.

    .venv/bin/python bench/turtlebot3d_bench.py [--seconds 20] [--points]

A kame master and `roslaunch turtlebot_gazebo turtlebot_world.launch gui:=false` (gzserver on
the playground, the Kobuki with its Kinect: 640x480 RGB and depth at 30 Hz, robot_state_publisher,
the velocity mux, depthimage_to_laserscan making /scan from the depth image). This process
subscribes to the colour image, the depth image and /scan (with --points, the PointCloud2 too),
so every sensor is rendered and sent, and drives the robot in a circle on /cmd_vel. Three windows
of --seconds each:
- as launched: turtlebot_description's Kinect plugin publishes at 10 Hz (its <updateRate>, as
  upstream's); the playground's <real_time_factor> of 1 and update rate of 1000 Hz pace the world
  as Gazebo's do, so 1.0 is the ceiling.
- the Kinect at 30 Hz: the robot deleted and spawned again (/gazebo/delete_model,
  /gazebo/spawn_urdf_model) from robot_description with the sensor's and plugin's rates at 30.
  Target >= 1.0 (paced: 0.98 or more is the pace held).
- the same unthrottled: /gazebo/set_physics_properties with max_update_rate 0 (Gazebo's "as fast
  as it can"), which shows the headroom.
Each window reports the real-time factor (simulated seconds of /clock per wall second), the
messages received per simulated second (30 for the images, 30 for /scan), each process's CPU
share of one core and gzserver's simulated seconds per CPU second (what a core of its own gives).

    .venv/bin/python bench/turtlebot3d_bench.py --profile [--seconds 5]

Where gzserver's time goes, in this process without ROS: the playground and the TurtleBot
(robot_description from turtlebot_description's xacro) stepped for --seconds of simulated time,
the Kinect at 30 Hz doing what its plugin does per frame (one render of colour and depth, read
back; the depth cut to the plugin's range as NaN; both images serialized as sensor_msgs/Image; the
PointCloud2 built and serialized), each part timed, with the plugin's own functions.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import subprocess
import sys
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from bench_procs import cpu_seconds, free_port, stop
from nav_bench import descendants

BIN = Path(sys.executable).parent
NODES = ("gazebo", "depthimage_to_laserscan", "robot_state_publisher", "cmd_vel_mux")


@dataclass
class Window:
    wall: float
    sim: float
    counts: dict[str, int]
    cpu: dict[str, float]

    @property
    def factor(self) -> float:
        return self.sim / self.wall


class Listener:
    """The bench's node: counts what arrives on each topic, keeps the latest /clock."""

    def __init__(self, topics: dict[str, Any]) -> None:
        import rospy
        from rosgraph_msgs.msg import Clock

        self.lock = threading.Lock()
        self.counts = dict.fromkeys(topics, 0)
        self.clock = 0.0
        self.clock_seen = threading.Event()
        rospy.Subscriber("/clock", Clock, self._on_clock, queue_size=1)
        for topic, data_class in topics.items():
            rospy.Subscriber(topic, data_class, self._counter(topic), queue_size=1)

    def _on_clock(self, msg: Any) -> None:
        with self.lock:
            self.clock = msg.clock.to_sec()
        self.clock_seen.set()

    def _counter(self, topic: str) -> Any:
        def count(_msg: Any) -> None:
            with self.lock:
                self.counts[topic] += 1
        return count

    def snapshot(self) -> tuple[float, dict[str, int]]:
        with self.lock:
            return self.clock, dict(self.counts)


def node_pids(root: int) -> dict[str, int]:
    found: dict[str, int] = {}
    for pid, line in descendants(root).items():
        for name in NODES:
            if f"__name:={name} " in line + " " and name not in found:
                found[name] = pid
    return found


def measure(listener: Listener, pids: dict[str, int], seconds: float) -> Window:
    cpu_before = {name: cpu_seconds(pid) for name, pid in pids.items()}
    cpu_before["bench"] = time.process_time()
    sim_before, counts_before = listener.snapshot()
    wall_before = time.monotonic()
    time.sleep(seconds)  # the window itself: the listener's threads count meanwhile
    sim_after, counts_after = listener.snapshot()
    wall = time.monotonic() - wall_before
    cpu = {name: cpu_seconds(pid) - cpu_before[name] for name, pid in pids.items()}
    cpu["bench"] = time.process_time() - cpu_before["bench"]
    return Window(wall, sim_after - sim_before, {t: counts_after[t] - counts_before[t] for t in counts_after}, cpu)


def report(title: str, window: Window) -> None:
    load = os.getloadavg()
    print(f"\n{title}: {window.wall:.1f} s of wall time, {window.sim:.2f} s simulated, "
          f"load average {load[0]:.1f}")
    print(f"real-time factor {window.factor:.2f}; gzserver: {window.sim / window.cpu['gazebo']:.2f} simulated s "
          f"per CPU s")
    for topic, count in window.counts.items():
        print(f"  {topic:28s} {count / window.sim if window.sim else 0:6.1f} per simulated s")
    for name, seconds in window.cpu.items():
        print(f"  CPU {name:24s} {100 * seconds / window.wall:5.0f}% of a core")


def respawn_at_30_hz() -> None:
    """The TurtleBot again, its Kinect's sensor and plugin rates at 30 Hz, where it stood."""
    import rospy
    from gazebo_msgs.srv import DeleteModel, GetModelState, SpawnModel

    urdf = rospy.get_param("/robot_description")
    faster = re.sub(r"<updateRate>[^<]*</updateRate>", "<updateRate>30</updateRate>", urdf)
    faster = re.sub(r"(<sensor[^>]*type=\"depth\"[^>]*>.*?<update_rate>)[^<]*(</update_rate>)", r"\g<1>30\g<2>",
                    faster, flags=re.S)
    if faster.count(">30<") < 2:
        raise RuntimeError("robot_description has no Kinect rates to change")
    pose = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)("mobile_base", "world").pose
    rospy.ServiceProxy("/gazebo/delete_model", DeleteModel)("mobile_base")
    rospy.ServiceProxy("/gazebo/spawn_urdf_model", SpawnModel)(
        model_name="mobile_base", model_xml=faster, robot_namespace="", initial_pose=pose, reference_frame="world")


def profile(seconds: float) -> None:
    """The per-frame parts of the Kinect's plugin, timed against the physics steps."""
    import io

    from kame.gazebo import Pose, World
    from kame.gazebo_ros.models import resources_from
    from kame.gazebo_ros.plugins.camera import depth_in_range, point_cloud_bytes
    from sensor_msgs.msg import Image, PointCloud2

    resources = resources_from(os.environ)
    assert resources.find_package is not None
    share, robots = (Path(resources.find_package(name) or "") for name in ("turtlebot_gazebo", "turtlebot_description"))
    description = subprocess.run([str(BIN / "xacro"), str(robots / "robots" / "kobuki_hexagons_kinect.urdf.xacro")],
                                 capture_output=True, text=True, check=True).stdout
    world = World.from_file(str(share / "worlds" / "playground.world"), resources)
    world.spawn_urdf(description, "mobile_base", Pose())
    camera = next(s for s in world.sensors() if s.type == "depth")
    f = 320 / math.tan(camera.config.child("camera").number("horizontal_fov", 1.047) / 2)
    world.drive_joint("mobile_base::wheel_left_joint", 4.0, 1.0)
    world.drive_joint("mobile_base::wheel_right_joint", 6.0, 1.0)
    parts = dict.fromkeys(("physics steps", "render + readback", "depth cut to range", "images serialized",
                           "point cloud built + serialized"), 0.0)
    frames = round(seconds * 30)
    steps_per_frame = round(1 / 30 / world.physics.max_step_size)
    started = time.perf_counter()
    for _ in range(frames):
        mark = time.perf_counter()
        world.step(steps_per_frame)
        now = time.perf_counter()
        parts["physics steps"] += now - mark
        frame = world.camera_frame(camera, rgb=True, depth=True)
        mark, now = now, time.perf_counter()
        parts["render + readback"] += now - mark
        depth = depth_in_range(frame.depth, 0.4, 8.0)
        mark, now = now, time.perf_counter()
        parts["depth cut to range"] += now - mark
        for pixels, encoding in ((frame.rgb, "rgb8"), (depth, "32FC1")):
            msg = Image(height=480, width=640, encoding=encoding, step=pixels.strides[0], data=pixels.tobytes())
            msg.serialize(io.BytesIO())
        mark, now = now, time.perf_counter()
        parts["images serialized"] += now - mark
        cloud = point_cloud_bytes(depth, frame.rgb, f, 320.0, 240.0)
        PointCloud2(height=480, width=640, point_step=16, row_step=16 * 640, data=cloud).serialize(io.BytesIO())
        parts["point cloud built + serialized"] += time.perf_counter() - now
    wall = time.perf_counter() - started
    world.close()
    print(f"{frames} frames over {seconds:.1f} simulated s in {wall:.2f} s of wall time "
          f"(real-time factor {seconds / wall:.2f} for these parts alone), load average {os.getloadavg()[0]:.1f}")
    for part, spent in parts.items():
        print(f"  {part:32s} {1000 * spent / frames:7.2f} ms a frame  {100 * spent / wall:5.1f}%")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--profile", action="store_true", help="where gzserver's time goes, in this process")
    parser.add_argument("--points", action="store_true", help="also subscribe to /camera/depth/points")
    parser.add_argument("--home", type=Path, default=Path("/tmp/kame-turtlebot3d-bench"))
    args = parser.parse_args()
    if args.profile:
        os.environ.setdefault("MUJOCO_GL", "egl")
        profile(args.seconds)
        return 0
    args.home.mkdir(parents=True, exist_ok=True)
    port = free_port()
    env = {**os.environ, "ROS_MASTER_URI": f"http://127.0.0.1:{port}/", "ROS_HOSTNAME": "127.0.0.1",
           "ROS_HOME": str(args.home)}
    env.setdefault("MUJOCO_GL", "egl")
    os.environ.update(env)
    procs: list[subprocess.Popen[str]] = []

    def start(*command: str) -> subprocess.Popen[str]:
        proc = subprocess.Popen(list(command), env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, text=True)
        procs.append(proc)
        return proc

    try:
        start(str(BIN / "rosmaster"), "--core", "-p", str(port))
        launch = start(str(BIN / "roslaunch"), "turtlebot_gazebo", "turtlebot_world.launch", "gui:=false")
        import rospy
        from gazebo_msgs.srv import GetPhysicsProperties, SetPhysicsProperties
        from geometry_msgs.msg import Twist
        from sensor_msgs.msg import Image, LaserScan, PointCloud2

        rospy.init_node("turtlebot3d_bench", anonymous=True, disable_signals=True)
        topics: dict[str, Any] = {"/camera/rgb/image_raw": Image, "/camera/depth/image_raw": Image,
                                  "/scan": LaserScan}
        if args.points:
            topics["/camera/depth/points"] = PointCloud2
        listener = Listener(topics)
        rospy.wait_for_service("/gazebo/set_physics_properties", timeout=120)
        if not listener.clock_seen.wait(120):
            raise RuntimeError("no /clock from gzserver")
        rospy.wait_for_message("/scan", LaserScan, timeout=120)
        commands = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
        circle = Twist()
        circle.linear.x, circle.angular.z = 0.2, 0.4
        driving = rospy.Timer(rospy.Duration(0.1), lambda _event: commands.publish(circle))
        pids = node_pids(launch.pid)
        time.sleep(2.0)  # settle: the subscriptions connected, the first frames out
        report("as launched (the Kinect at 10 Hz, real_time_factor 1, update rate 1000 Hz)",
               measure(listener, pids, args.seconds))

        respawn_at_30_hz()
        rospy.wait_for_message("/scan", LaserScan, timeout=120)
        time.sleep(2.0)
        report("the Kinect at 30 Hz, paced", measure(listener, pids, args.seconds))

        properties = rospy.ServiceProxy("/gazebo/get_physics_properties", GetPhysicsProperties)()
        rospy.ServiceProxy("/gazebo/set_physics_properties", SetPhysicsProperties)(
            time_step=properties.time_step, max_update_rate=0.0, gravity=properties.gravity,
            ode_config=properties.ode_config)
        time.sleep(2.0)
        report("the Kinect at 30 Hz, unthrottled (max_update_rate 0)", measure(listener, pids, args.seconds))
        driving.shutdown()
        rospy.signal_shutdown("bench done")
    finally:
        for proc in reversed(procs):
            stop(proc, grace=15)
    return 0


if __name__ == "__main__":
    sys.exit(main())
