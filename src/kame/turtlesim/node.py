"""turtlesim_node: the ROS face of a turtlesim world, with or without its window.

    rosrun turtlesim turtlesim_node [--headless] [__name:=NAME] [remappings]

The glue of ARCHITECTURE rule 4: the world (kame.turtlesim.world) simulates, the GUI
(kame.turtlesim.gui) draws snapshots, and this module turns ROS traffic into world requests
and world steps into ROS traffic, as turtlesim 0.10.2's TurtleFrame and Turtle do:
- node `turtlesim`; services clear, reset, spawn, kill; params ~background_r/g/b (set to
  69/86/255 when absent, read at start and on every clear/reset);
- per turtle: cmd_vel in, pose and color_sensor out (every 16 ms step), services set_pen,
  teleport_absolute, teleport_relative (ROS 1's turtlesim has no action: rotate_absolute is
  ROS 2's);
- roscpp's log lines; errors are logged and answered as failed calls with no text, as a
  roscpp service returning false is.
What kame adds: a cmd_vel or request with NaN/infinity is refused (the real turtle would
vanish into NaN); the pre-0.9.2 global /background_r etc. of older tutorials are honoured
while the private ones keep the values turtlesim gave them; with no display, or --headless,
or without PySide6, or when a probe child finds that Qt cannot open a window (a missing system
library, a Qt binding known to crash), the simulation runs without a window and says why once.
The window is a process of its own, fed snapshots (kame.net.feed): when it dies (its X server
gone) the simulation goes on headless and says so; when the user closes it, turtlesim ends.
"""

from __future__ import annotations

import io
import os
import sys
import threading
import time
from collections.abc import Callable, Sequence
from typing import Any

from geometry_msgs.msg import Twist
from kame.catkin import executables
from kame.client import core, log, process, topics
from kame.net.feed import ChildFeed
from kame.net.window import window_problem
from kame.turtlesim.canvas import Rgb
from kame.turtlesim.frame_codec import FrameEncoder
from kame.turtlesim.world import (
    DEFAULT_BACKGROUND,
    UPDATE_PERIOD,
    Snapshot,
    StepReport,
    TurtleError,
    World,
)
from std_srvs.srv import Empty, EmptyResponse
from turtlesim.msg import Color
from turtlesim.msg import Pose as PoseMsg
from turtlesim.srv import (
    Kill,
    KillResponse,
    SetPen,
    SetPenResponse,
    Spawn,
    SpawnResponse,
    TeleportAbsolute,
    TeleportAbsoluteResponse,
    TeleportRelative,
    TeleportRelativeResponse,
)

NODE_NAME = "turtlesim"
WINDOW_TITLE = "TurtleSim"
_CHANNELS = ("r", "g", "b")


def _info(msg: str, *args: Any) -> None:
    log.emit(log.INFO, msg, args)


def _warn(msg: str, *args: Any) -> None:
    log.emit(log.WARN, msg, args)


def _error(msg: str, *args: Any) -> None:
    log.emit(log.ERROR, msg, args)


def _serialized(msg: Any) -> bytes:
    buff = io.BytesIO()
    msg.serialize(buff)
    return buff.getvalue()


class _TurtleInterfaces:
    """One turtle's topics and services, under `<name>/`."""

    def __init__(self, sim: TurtlesimNode, name: str) -> None:
        self.name = name
        self.pose = topics.Publisher(f"{name}/pose", PoseMsg, queue_size=1)
        self.color = topics.Publisher(f"{name}/color_sensor", Color, queue_size=1)
        self.cmd_vel = topics.Subscriber(f"{name}/cmd_vel", Twist, self._on_cmd_vel, queue_size=1)
        self._sim = sim
        self.services = [
            sim.serve(f"{name}/set_pen", SetPen, self._set_pen),
            sim.serve(f"{name}/teleport_absolute", TeleportAbsolute, self._teleport_absolute),
            sim.serve(f"{name}/teleport_relative", TeleportRelative, self._teleport_relative),
        ]

    def _on_cmd_vel(self, msg: Twist) -> None:
        try:
            with self._sim.lock:
                self._sim.world.command(self.name, msg.linear.x, msg.linear.y, msg.angular.z)
        except TurtleError as exc:
            _warn("Ignoring a cmd_vel for [%s]: %s", self.name, exc)

    def _set_pen(self, req: Any) -> SetPenResponse:
        with self._sim.lock:
            self._sim.world.set_pen(self.name, req.r, req.g, req.b, req.width, bool(req.off))
        return SetPenResponse()

    def _teleport_absolute(self, req: Any) -> TeleportAbsoluteResponse:
        with self._sim.lock:
            self._sim.world.teleport_absolute(self.name, req.x, req.y, req.theta)
        return TeleportAbsoluteResponse()

    def _teleport_relative(self, req: Any) -> TeleportRelativeResponse:
        with self._sim.lock:
            self._sim.world.teleport_relative(self.name, req.linear, req.angular)
        return TeleportRelativeResponse()

    def publish(self, pose: Any, color: Rgb) -> None:
        self.pose.publish(PoseMsg(pose.x, pose.y, pose.theta, pose.linear_velocity, pose.angular_velocity))
        self.color.publish(Color(color.r, color.g, color.b))

    def close(self) -> None:
        self.pose.unregister()
        self.color.unregister()
        self.cmd_vel.unregister()
        node = core.get_node()
        for service in self.services:
            if node is not None:
                node.unadvertise_service(service)


class TurtlesimNode:
    """Steps a World every UPDATE_PERIOD and keeps its turtles' ROS interfaces in step with it.
    Callbacks arrive on I/O threads: the world is touched only under `lock`."""

    def __init__(self, world: World) -> None:
        self.world = world
        self.lock = threading.Lock()
        self._sync_lock = threading.Lock()
        self._turtles: dict[str, _TurtleInterfaces] = {}  # replaced whole, read without a lock
        self._initial_background: dict[str, Any] = {}
        self._drawn = -1

    # ---------------------------------------------------------------- start-up

    def start(self) -> None:
        _info("Starting turtlesim with node name %s", core.get_name())
        for channel, default in zip(_CHANNELS, (DEFAULT_BACKGROUND.r, DEFAULT_BACKGROUND.g, DEFAULT_BACKGROUND.b),
                                    strict=True):
            key = f"~background_{channel}"
            if not process.has_param(key):
                process.set_param(key, default)
            self._initial_background[channel] = process.get_param(key, default)
        self.serve("clear", Empty, self._clear)
        self.serve("reset", Empty, self._reset_service)
        self.serve("spawn", Spawn, self._spawn)
        self.serve("kill", Kill, self._kill)
        self._reset()

    def serve(self, name: str, service_class: Any, handler: Callable[[Any], Any]) -> str:
        """Advertise a service whose handler's TurtleError is logged and answered as a plain
        failure (roscpp's `return false`)."""
        resolved = core.resolve_name(name)
        request_class = service_class._request_class

        def handle(data: bytes) -> tuple[bool, bytes | str]:
            try:
                request = request_class().deserialize(data)
            except Exception as exc:
                return False, f"error processing request: {exc}"
            try:
                return True, _serialized(handler(request))
            except TurtleError as exc:
                _error("%s", exc)
                return False, ""

        node = core.get_node()
        assert node is not None
        node.advertise_service(resolved, service_class._type, service_class._md5sum, handle)
        return resolved

    # ---------------------------------------------------------------- services

    def background(self) -> Rgb:
        values = []
        for channel in _CHANNELS:
            private = process.get_param(f"~background_{channel}", self._initial_background.get(channel))
            legacy = process.get_param(f"background_{channel}", None)
            value = legacy if legacy is not None and private == self._initial_background.get(channel) else private
            try:
                values.append(int(value) & 0xFF)
            except (TypeError, ValueError):
                values.append(getattr(DEFAULT_BACKGROUND, channel))
        return Rgb(*values)

    def _clear(self, _req: Any) -> EmptyResponse:
        _info("Clearing turtlesim.")
        background = self.background()
        with self.lock:
            self.world.clear(background)
        return EmptyResponse()

    def _reset_service(self, _req: Any) -> EmptyResponse:
        _info("Resetting turtlesim.")
        self._reset()
        return EmptyResponse()

    def _reset(self) -> None:
        background = self.background()
        with self.lock:
            name = self.world.reset(background)
            pose = self.world.turtle(name).pose
        self._log_spawn(name, pose.x, pose.y, pose.theta)
        self._sync()

    def _spawn(self, req: Any) -> SpawnResponse:
        with self.lock:
            name = self.world.spawn(req.name, req.x, req.y, req.theta)
        self._log_spawn(name, req.x, req.y, req.theta)
        self._sync()
        return SpawnResponse(name)

    def _kill(self, req: Any) -> KillResponse:
        with self.lock:
            self.world.kill(req.name)
        self._sync()
        return KillResponse()

    @staticmethod
    def _log_spawn(name: str, x: float, y: float, theta: float) -> None:
        _info("Spawning turtle [%s] at x=[%f], y=[%f], theta=[%f]", name, x, y, theta)

    def _sync(self) -> None:
        """Give every turtle of the world its interfaces, and take them from turtles gone."""
        with self._sync_lock:
            with self.lock:
                names = set(self.world.names())
            current = dict(self._turtles)
            for gone in sorted(set(current) - names):
                current.pop(gone).close()
            self._turtles = current
            for new in sorted(names - set(current)):
                current[new] = _TurtleInterfaces(self, new)
                self._turtles = dict(current)

    # ---------------------------------------------------------------- time

    def tick(self) -> StepReport:
        """One simulation step, then its pose, colour and warning traffic."""
        with self.lock:
            report = self.world.step(UPDATE_PERIOD)
        turtles = self._turtles
        for update in report.updates:
            interfaces = turtles.get(update.name)
            if interfaces is not None:
                interfaces.publish(update.pose, update.color)
        for hit in report.hits:
            _warn("Oh no! I hit the wall! (Clamping from [x=%f, y=%f])", hit.x, hit.y)
        return report

    def frame(self) -> Snapshot | None:
        """A step for a window: the new snapshot when something visible changed, else None."""
        self.tick()
        with self.lock:
            if self.world.version == self._drawn:
                return None
            self._drawn = self.world.version
            return self.world.snapshot()

    def run(self, show: Callable[[Snapshot], None] | None = None) -> None:
        """Step every UPDATE_PERIOD until shutdown, handing `show` each snapshot that differs from
        the last; a late step is not made up for by a burst."""
        deadline = time.monotonic()
        while not core.is_shutdown():
            if show is None:
                self.tick()
            elif (snapshot := self.frame()) is not None:
                show(snapshot)
            deadline += UPDATE_PERIOD
            delay = deadline - time.monotonic()
            if delay < -0.1:
                deadline = time.monotonic()
            elif delay > 0:
                core.wait_for_shutdown(delay)

    def shutdown(self) -> None:
        with self._sync_lock:
            for interfaces in self._turtles.values():
                interfaces.close()
            self._turtles = {}


def window_command() -> list[str]:
    """The window process, with turtlesim's images/ found as turtlesim finds its package (the
    first turtlesim on ROS_PACKAGE_PATH, else kame's own)."""
    images = executables.packages(os.environ)["turtlesim"].path / "images"
    return [sys.executable, "-m", "kame.turtlesim.gui", "--window", WINDOW_TITLE, str(images)]


def open_window() -> ChildFeed[Snapshot]:
    """The window, a process of its own fed snapshots: when it dies, the simulation goes on."""
    encoder = FrameEncoder()

    def ended(status: int) -> None:
        if status == 0:  # the user closed it: turtlesim ends, as ROS's does
            core.signal_shutdown("window closed")
            return
        how = f"signal {-status}" if status < 0 else f"status {status}"
        _warn("The window ended (%s): turtlesim continues headless, without a window", how)

    return ChildFeed(window_command(), encoder.encode, ended)


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    args = process.myargv(argv)[1:]
    log.use_roscpp_console()
    process.init_node(NODE_NAME, argv=argv)
    sim = TurtlesimNode(World())
    sim.start()
    problem = window_problem("turtlesim", "--headless" if "--headless" in args else None, os.environ)
    window = None
    try:
        if problem is not None:
            (_info if problem.asked_for else _warn)("%s", problem.reason)
        else:
            window = open_window()
        sim.run(show=window.offer if window is not None else None)
    except KeyboardInterrupt:
        pass
    finally:
        if window is not None:
            window.close()
        sim.shutdown()
        core.signal_shutdown("turtlesim exiting")
    return 0


if __name__ == "__main__":
    sys.exit(main())
