"""stageros: the ROS face of kame's 2-D world (kame.stage.world), standing in for Stage and Gazebo.

    rosrun stage_ros stageros [-g] [-u] [--stand-in-for gazebo] map.yaml|stage.world [remappings]

The world is a map_server map (its occupied cells are walls) or a Stage .world file (its
floorplan bitmap, boxes and robots: kame.stage.worldfile). Per robot (topics unprefixed for
one robot, under robot_<i>/ or the given names for several, as stageros names them):
  in:  cmd_vel (geometry_msgs/Twist; linear.x, angular.z), dropped after ~base_watchdog_timeout
       seconds of simulated time without a new one; ~extra_cmd_vel_topics listens on more names
       (turtlebot_gazebo: mobile_base/commands/velocity, cmd_vel_mux/input/teleop ...);
  out: odom (nav_msgs/Odometry, drifting), base_pose_ground_truth (nav_msgs/Odometry, the truth
       in the map frame), base_scan (sensor_msgs/LaserScan at the laser's rate; stageros's name,
       turtlebot_world.launch remaps it to scan), bumper (std_msgs/Bool,
       latched, on each change: true while a wall or robot stops it);
and for all: /tf (tf2_msgs/TFMessage: odom -> base_footprint -> base_link -> base_scan per
robot), /clock (rosgraph_msgs/Clock, every step; set /use_sim_time to follow it).
Private params: ~initial_pose_x/y/a (one robot) or ~robots ([{name, x, y, a}, ...]);
~laser_beams, ~laser_angle_min/max, ~laser_range_min/max, ~laser_rate, ~laser_noise;
~odom_drift_linear/angular, ~seed; ~boxes ([[x, y, width, depth], ...]: obstacles added to the
world that its map does not show, as one places a box in Gazebo); the service ~add_box
(kame_stage_msgs/AddBox: x, y, width, depth -> success, message) places one while it runs;
the service reset_positions (std_srvs/Empty, in the node's namespace as stageros's) puts every
robot back at its start pose, its ground truth and odometry as at start (World.reset_positions);
~step (seconds of simulated time, 0.01), ~odom_rate (Hz, 50);
~real_time_factor (1.0; 0 runs as fast as it can); ~odom_frame_id, ~base_frame_id, ~laser_frame_id.
The window (as Stage's: the world from above, robots, laser hits) is a process of its own fed
frames (kame.net.feed, kame.stage.gui); -g runs without it, as does a machine without a display
or PySide6 (said once). Closing the window ends stageros, as closing Stage's does; a window
that dies otherwise leaves the simulation running. -u is accepted for stageros's command lines.
Bad input (no map, a robot in a wall, a NaN command) is an error line, never a traceback.
"""

from __future__ import annotations

import math
import os
import sys
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from kame.launch.substitution import installed
from kame.names import is_legal_base_name
from kame.net.feed import ChildFeed
from kame.net.window import window_problem
from kame.stage import runtime
from kame.stage.map_server import read_map
from kame.stage.mapfile import Grid, MapError, decode_image
from kame.stage.view import Frame, FrameEncoder, frame_of, scan_hits, wall_raster
from kame.stage.world import LaserModel, OdometryModel, Pose, RobotState, Walls, World, WorldError
from kame.stage.worldfile import WorldFileError, rasterise
from kame.stage.worldfile import parse as parse_world_file

USAGE = "Usage: stageros [-g] [-u] [--stand-in-for gazebo] <map.yaml | world.world>"
BASE_LINK_HEIGHT = 0.0102  # base_footprint -> base_link, as turtlebot_description's Kobuki
LASER_HEIGHT = 0.287  # base_link -> base_scan: the Kinect's height on a TurtleBot 2


class SetupError(ValueError):
    """A command line or parameter the simulator cannot start with."""


# the one line a TurtleBot user without MuJoCo sees (turtlebot_world.launch runs the 3-D world with it)
GAZEBO_HINT = "For the 3-D TurtleBot world on kame's Gazebo: pip install 'kame[gazebo]'"
WINDOW_PERIOD = 0.05  # seconds of wall time between the window's frames (20 Hz)


@dataclass(frozen=True)
class Options:
    map_path: str
    stand_in_for: str | None
    headless: bool = False


def parse_args(args: Sequence[str]) -> Options:
    rest = [a for a in args if a not in ("-g", "-u")]
    stand_in = None
    if "--stand-in-for" in rest:
        i = rest.index("--stand-in-for")
        if i + 1 >= len(rest):
            raise SetupError(USAGE)
        stand_in = rest[i + 1]
        del rest[i:i + 2]
    if len(rest) != 1:
        raise SetupError(USAGE)
    return Options(rest[0], stand_in, "-g" in args)


def _number(name: str, default: float) -> float:
    value = runtime.get_param(name, default)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise SetupError(f"parameter {runtime.resolve_name(name)} must be a finite number, not {value!r}")
    return float(value)


Placement = tuple[str, float, float, float]  # namespace, x, y, yaw


def robot_placements(from_world: Sequence[Placement] = ()) -> list[Placement]:
    """Each robot's namespace and pose: ~robots when set, else the world file's robots, else one
    robot at ~initial_pose_*."""
    robots = runtime.get_param("~robots", None)
    if robots is None and from_world:
        return list(from_world)
    if robots is None:
        return [("", _number("~initial_pose_x", 0.0), _number("~initial_pose_y", 0.0),
                 _number("~initial_pose_a", 0.0))]
    if not isinstance(robots, list) or not robots:
        raise SetupError("parameter ~robots must be a list of {name, x, y, a}")
    placements = []
    for i, entry in enumerate(robots):
        if not isinstance(entry, dict):
            raise SetupError(f"~robots[{i}] must be a mapping {{name, x, y, a}}, not {entry!r}")
        values = [entry.get(k, 0.0) for k in ("x", "y", "a")]
        if not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in values):
            raise SetupError(f"~robots[{i}]: x, y and a must be finite numbers")
        x, y, yaw = (float(v) for v in values)
        name = str(entry.get("name", f"robot_{i}"))
        if not is_legal_base_name(name):
            raise SetupError(f"~robots[{i}]: {name!r} is not a legal ROS name for a robot's namespace")
        placements.append((name, x, y, yaw))
    return placements


def read_stage_world(path: str) -> tuple[Grid, list[Placement]]:
    """The grid and robots of a Stage .world file (includes and bitmaps beside it); robots are
    unprefixed when alone, else robot_0, robot_1... as stageros names them."""
    folder = os.path.dirname(path)

    def read(name: str) -> str:
        with open(os.path.join(folder, name), encoding="utf-8") as f:
            return f.read()

    try:
        text = read(os.path.basename(path))
    except (OSError, UnicodeDecodeError) as exc:
        raise SetupError(f"cannot open the world file {path}: {exc}") from None
    spec = parse_world_file(text, path, read)
    bitmaps = {}
    for plan in spec.floorplans:
        image = os.path.join(folder, plan.bitmap)
        try:
            with open(image, "rb") as f:
                data = f.read()
        except OSError as exc:
            raise MapError(f'Failed to open image file "{image}": {exc.strerror or exc}') from None
        bitmaps[plan.bitmap], _ = decode_image(data, image)
    robots = spec.robots
    return rasterise(spec, bitmaps), [("" if len(robots) == 1 else f"robot_{i}", *robot.pose)
                                      for i, robot in enumerate(robots)]


def make_world(map_path: str) -> tuple[World, list[Placement]]:
    """The world of a map_server map or a Stage .world file, and the robots the file places."""
    placements: list[Placement] = []
    if map_path.endswith(".world"):
        grid, placements = read_stage_world(map_path)
    else:
        grid = read_map(map_path)
    laser = LaserModel(
        beams=int(_number("~laser_beams", LaserModel.beams)),
        angle_min=_number("~laser_angle_min", LaserModel.angle_min),
        angle_max=_number("~laser_angle_max", LaserModel.angle_max),
        range_min=_number("~laser_range_min", LaserModel.range_min),
        range_max=_number("~laser_range_max", LaserModel.range_max),
        rate=_number("~laser_rate", LaserModel.rate),
        noise=_number("~laser_noise", LaserModel.noise))
    odometry = OdometryModel(_number("~odom_drift_linear", OdometryModel.linear),
                             _number("~odom_drift_angular", OdometryModel.angular))
    walls = Walls(grid)
    boxes = runtime.get_param("~boxes", [])
    if not isinstance(boxes, list) or not all(isinstance(b, list) and len(b) == 4 for b in boxes):
        raise SetupError("parameter ~boxes must be a list of [x, y, width, depth]")
    for box in boxes:
        try:
            walls.add_box(*(float(v) for v in box))
        except (TypeError, ValueError) as exc:
            raise SetupError(f"parameter ~boxes: {exc}") from None
    world = World(walls, laser=laser, odometry=odometry,
                  command_timeout=_number("~base_watchdog_timeout", 0.5), seed=int(_number("~seed", 0)))
    return world, placements


def _stamp(seconds: float) -> Any:
    nanoseconds = round(seconds * 1e9)  # the sum of many float steps, rounded to the clock's unit
    return runtime.Time(nanoseconds // 1_000_000_000, nanoseconds % 1_000_000_000)


def _quaternion(yaw: float) -> tuple[float, float]:
    return math.sin(yaw / 2), math.cos(yaw / 2)


def _prefixed(namespace: str, name: str) -> str:
    return f"{namespace}/{name}" if namespace else name


class _RobotInterfaces:
    """One robot's topics."""

    def __init__(self, sim: Simulator, name: str, namespace: str) -> None:
        from geometry_msgs.msg import Twist
        from nav_msgs.msg import Odometry
        from sensor_msgs.msg import LaserScan
        from std_msgs.msg import Bool

        self.name = name
        self.namespace = namespace
        self._sim = sim
        self.odom = runtime.Publisher(_prefixed(namespace, "odom"), Odometry, queue_size=10)
        self.truth = runtime.Publisher(_prefixed(namespace, "base_pose_ground_truth"), Odometry, queue_size=10)
        self.scan = runtime.Publisher(_prefixed(namespace, "base_scan"), LaserScan, queue_size=10)
        self.bumper = runtime.Publisher(_prefixed(namespace, "bumper"), Bool, queue_size=10, latch=True)
        self.bumper.publish(Bool(False))
        self.stalled = False
        topics = ["cmd_vel", *sim.extra_cmd_vel_topics]
        self.commands = [runtime.Subscriber(_prefixed(namespace, t), Twist, self._on_cmd_vel, queue_size=1)
                         for t in topics]

    def _on_cmd_vel(self, msg: Any) -> None:
        try:
            with self._sim.lock:
                self._sim.world.command(self.name, msg.linear.x, msg.angular.z)
        except WorldError as exc:
            runtime.warn_throttle(1.0, "Ignoring a cmd_vel for [%s]: %s", self.name, exc)

    def frame(self, name: str) -> str:
        return _prefixed(self.namespace, name)


class Simulator:
    """Steps a World and turns its states into ROS traffic. Callbacks arrive on I/O threads: the
    world is touched only under `lock`."""

    def __init__(self, world: World, step: float, odom_rate: float, real_time_factor: float,
                 extra_cmd_vel_topics: Sequence[str] = (),
                 frames: tuple[str, str, str, str] = ("odom", "base_footprint", "base_link", "base_scan")) -> None:
        if not (step > 0) or not (odom_rate > 0) or not (real_time_factor >= 0):
            raise SetupError("~step and ~odom_rate must be above 0, ~real_time_factor at least 0")
        self.world = world
        self.step_seconds = step
        self.real_time_factor = real_time_factor
        self.extra_cmd_vel_topics = list(extra_cmd_vel_topics)
        self.lock = threading.Lock()
        self._odom_every = max(1, round(1.0 / (odom_rate * step)))
        self._scan_every = max(1, round(1.0 / (world.laser.rate * step)))
        self._steps = 0
        self._robots: list[_RobotInterfaces] = []
        self.frames = frames
        self._tf: Any = None
        self._clock: Any = None
        self._hits: dict[str, bytes] = {}  # each robot's last scan, as the window shows it
        self._raster: bytes | None = None

    def robot_names(self) -> list[str]:
        return [r.name for r in self._robots]

    def start(self, placements: Sequence[tuple[str, float, float, float]], publish_clock: bool) -> None:
        from rosgraph_msgs.msg import Clock
        from tf2_msgs.msg import TFMessage

        for namespace, x, y, yaw in placements:
            name = namespace or "robot_0"
            with self.lock:
                self.world.spawn(name, x, y, yaw)
            self._robots.append(_RobotInterfaces(self, name, namespace))
        self._tf = runtime.Publisher("/tf", TFMessage, queue_size=100)
        self._clock = runtime.Publisher("/clock", Clock, queue_size=10) if publish_clock else None
        from kame_stage_msgs.srv import AddBox

        runtime.Service("~add_box", AddBox, self._on_add_box)
        from std_srvs.srv import Empty

        runtime.Service("reset_positions", Empty, self._on_reset_positions)

    def _on_reset_positions(self, _request: Any) -> Any:
        from std_srvs.srv import EmptyResponse

        runtime.info("Resetting stage!")  # stageros's words
        with self.lock:
            self.world.reset_positions()
        return EmptyResponse()

    def _on_add_box(self, request: Any) -> Any:
        from kame_stage_msgs.srv import AddBoxResponse

        box = (request.x, request.y, request.width, request.depth)
        try:
            with self.lock:
                self.world.add_box(*box)
                self._raster = None  # the window draws the walls anew, box included
        except WorldError as exc:
            return AddBoxResponse(False, str(exc))
        runtime.info("Placed a box of %g x %g m at (%g, %g)", request.width, request.depth, request.x, request.y)
        return AddBoxResponse(True, "")

    # ---------------------------------------------------------------- messages

    def _transform(self, stamp: Any, parent: str, child: str, x: float, y: float, z: float, yaw: float) -> Any:
        from geometry_msgs.msg import TransformStamped

        t = TransformStamped()
        t.header.stamp = stamp
        t.header.frame_id = parent
        t.child_frame_id = child
        t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = x, y, z
        t.transform.rotation.z, t.transform.rotation.w = _quaternion(yaw)
        return t

    @staticmethod
    def _odometry(stamp: Any, frame: str, child: str, pose: Pose, state: RobotState) -> Any:
        from nav_msgs.msg import Odometry

        msg = Odometry()
        msg.header.stamp = stamp
        msg.header.frame_id = frame
        msg.child_frame_id = child
        msg.pose.pose.position.x, msg.pose.pose.position.y = pose.x, pose.y
        msg.pose.pose.orientation.z, msg.pose.pose.orientation.w = _quaternion(pose.theta)
        msg.twist.twist.linear.x = state.linear
        msg.twist.twist.angular.z = state.angular
        return msg

    def _scan(self, stamp: Any, frame: str, ranges: Any) -> Any:
        from sensor_msgs.msg import LaserScan

        laser = self.world.laser
        msg = LaserScan()
        msg.header.stamp = stamp
        msg.header.frame_id = frame
        msg.angle_min, msg.angle_max, msg.angle_increment = laser.angle_min, laser.angle_max, laser.angle_increment
        msg.time_increment = 0.0
        msg.scan_time = 1.0 / laser.rate
        msg.range_min, msg.range_max = laser.range_min, laser.range_max
        msg.ranges = ranges.astype("float32")  # float32[] takes the array whole: no list per scan
        return msg

    # ---------------------------------------------------------------- time

    def tick(self) -> None:
        """One step of the world, then the traffic due at this step."""
        from std_msgs.msg import Bool
        from tf2_msgs.msg import TFMessage

        with self.lock:
            states = {s.name: s for s in self.world.step(self.step_seconds)}
            now = self.world.time
            self._steps += 1
            scans = self.world.scans() if self._steps % self._scan_every == 0 else {}
            if scans and self._raster is not None:
                self._hits = {name: scan_hits(self.world, name, ranges) for name, ranges in scans.items()}
        stamp = _stamp(now)
        if self._clock is not None:
            from rosgraph_msgs.msg import Clock

            self._clock.publish(Clock(stamp))
        odom_due = self._steps % self._odom_every == 0
        transforms = []
        odom_frame, base_footprint, base_link, base_scan = self.frames
        for robot in self._robots:
            state = states[robot.name]
            if state.stalled != robot.stalled:
                robot.stalled = state.stalled
                robot.bumper.publish(Bool(state.stalled))
            if odom_due:
                robot.odom.publish(self._odometry(stamp, robot.frame(odom_frame), robot.frame(base_footprint),
                                                  state.odom, state))
                robot.truth.publish(self._odometry(stamp, "map", robot.frame(base_footprint), state.pose, state))
                transforms += [
                    self._transform(stamp, robot.frame(odom_frame), robot.frame(base_footprint),
                                    state.odom.x, state.odom.y, 0.0, state.odom.theta),
                    self._transform(stamp, robot.frame(base_footprint), robot.frame(base_link),
                                    0.0, 0.0, BASE_LINK_HEIGHT, 0.0),
                    self._transform(stamp, robot.frame(base_link), robot.frame(base_scan),
                                    self.world.laser.mount_x, self.world.laser.mount_y, LASER_HEIGHT, 0.0)]
            if robot.name in scans:
                robot.scan.publish(self._scan(stamp, robot.frame(base_scan), scans[robot.name]))
        if transforms:
            self._tf.publish(TFMessage(transforms))

    def frame(self) -> Frame:
        """The world as the window draws it now."""
        with self.lock:
            if self._raster is None:
                self._raster = wall_raster(self.world)
            return frame_of(self.world, self._raster, self._hits)

    def run(self, show: Callable[[Frame], None] | None = None) -> None:
        """Step until shutdown, each step lasting step / real_time_factor of wall time (no waiting
        at factor 0); a late step is not made up for by a burst. `show` gets a frame every
        WINDOW_PERIOD of wall time."""
        pace = self.step_seconds / self.real_time_factor if self.real_time_factor > 0 else 0.0
        deadline = time.monotonic()
        next_frame = deadline
        while not runtime.is_shutdown():
            self.tick()
            if show is not None and time.monotonic() >= next_frame:
                show(self.frame())
                next_frame = time.monotonic() + WINDOW_PERIOD
            if pace == 0.0:
                continue
            deadline += pace
            delay = deadline - time.monotonic()
            if delay < -0.1:
                deadline = time.monotonic()
            elif delay > 0 and runtime.wait_for_shutdown(delay):
                break


def open_window(title: str) -> ChildFeed[Frame]:
    """The window, a process of its own fed frames: when it dies, the simulation goes on."""
    encoder = FrameEncoder()

    def ended(status: int) -> None:
        if status == 0:  # the user closed it: stageros ends, as Stage does
            runtime.signal_shutdown("window closed")
            return
        how = f"signal {-status}" if status < 0 else f"status {status}"
        runtime.warn("The window ended (%s): stageros continues headless, without a window", how)

    return ChildFeed([sys.executable, "-m", "kame.stage.gui", "--window", title], encoder.encode, ended)


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    try:
        options = parse_args(runtime.without_remappings(argv)[1:])
    except SetupError as exc:
        print(exc, file=sys.stderr)
        return 1
    runtime.init("stageros", argv)
    try:
        if options.stand_in_for:
            runtime.info("This is kame's 2-D world (stageros) standing in for %s: a flat world from %s, "
                         "with odometry, a laser scanner and walls, and no 3-D physics.",
                         options.stand_in_for.capitalize(), options.map_path)
            if options.stand_in_for == "gazebo" and not installed("mujoco"):
                runtime.info("%s", GAZEBO_HINT)
        world, from_file = make_world(options.map_path)
        extra = runtime.get_param("~extra_cmd_vel_topics", [])
        if not isinstance(extra, list) or not all(isinstance(t, str) for t in extra):
            raise SetupError("parameter ~extra_cmd_vel_topics must be a list of topic names")
        frames = (str(runtime.get_param("~odom_frame_id", "odom")),
                  str(runtime.get_param("~base_frame_id", "base_footprint")), "base_link",
                  str(runtime.get_param("~laser_frame_id", "base_scan")))
        sim = Simulator(world, _number("~step", 0.01), _number("~odom_rate", 50.0),
                        _number("~real_time_factor", 1.0), extra, frames)
        sim.start(robot_placements(from_file), bool(runtime.get_param("~publish_clock", True)))
    except (MapError, WorldError, WorldFileError, SetupError) as exc:
        runtime.error("%s", exc)
        runtime.signal_shutdown("cannot start")
        return 1
    names = ", ".join(f"[{name}]" for name in sim.robot_names())
    runtime.info("Simulating %s in %s (%d x %d cells of %g m)", names, options.map_path,
                 world.walls.occupied.shape[1], world.walls.occupied.shape[0], world.walls.resolution)
    problem = window_problem("stageros", "-g" if options.headless else None, os.environ)
    window = None
    try:
        if problem is not None:
            (runtime.info if problem.asked_for else runtime.warn)("%s", problem.reason)
        else:
            window = open_window(f"Stage: {os.path.basename(options.map_path)}")
        sim.run(show=window.offer if window is not None else None)
    except KeyboardInterrupt:
        pass
    finally:
        if window is not None:
            window.close()
        runtime.signal_shutdown("stageros exiting")
    return 0


if __name__ == "__main__":
    sys.exit(main())
