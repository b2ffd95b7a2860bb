"""gzserver with gazebo_ros's API: kame's 3-D simulator as the ROS node /gazebo.

    rosrun gazebo_ros gzserver [-u] [--verbose] [-e ode] [world_file] [remappings]

Loads the world (a path, or a name on GAZEBO_RESOURCE_PATH such as worlds/empty.world, or one of
kame's shipped worlds), starts its models' plugins, steps it on a thread this module owns at the
world's real_time_factor (paused with -u until /gazebo/unpause_physics), publishes /clock
(every step, or at ~pub_clock_frequency Hz of simulated time when set), and serves the /gazebo
API (kame.gazebo_ros.api), ~performance_metrics and what gzclient windows draw
(kame.gazebo_ros.client_feed) unless ~enable_ros_network is false. A world that cannot be read is
an error line, and the server runs on with an empty world, so models can still be spawned.
"""

from __future__ import annotations

import math
import os
import sys
import time
from collections.abc import Sequence
from pathlib import Path

from kame.client import core, process, topics
from kame.client import log as _log
from kame.gazebo.errors import GazeboError
from kame.gazebo.world import World
from kame.gazebo_ros import command_line
from kame.gazebo_ros.api import GazeboApi
from kame.gazebo_ros.client_feed import ClientFeed
from kame.gazebo_ros.conversions import stamp
from kame.gazebo_ros.models import ModelFactory, resources_from, world_file
from kame.gazebo_ros.plugins import PluginHost
from kame.gazebo_ros.simulation import Simulation

SHIPPED_WORLDS = str(Path(__file__).resolve().parents[1] / "share" / "gazebo_ros")


def _info(text: str) -> None:
    _log.emit(_log.INFO, "%s", (text,))


def _warn(text: str) -> None:
    _log.emit(_log.WARN, "%s", (text,))


def _error(text: str) -> None:
    _log.emit(_log.ERROR, "%s", (text,))


class ClockPublisher:
    """/clock after each step, or at most `frequency` times a second of simulated time."""

    def __init__(self, frequency: float) -> None:
        from rosgraph_msgs.msg import Clock

        self.period = 1.0 / frequency if frequency > 0 else 0.0
        self._last = -math.inf
        self.clock = topics.Publisher("/clock", Clock, queue_size=10)

    def __call__(self, now: float) -> None:
        from rosgraph_msgs.msg import Clock

        if now < self._last:  # reset_simulation: time starts again
            self._last = -math.inf
        if now - self._last + 1e-9 < self.period:
            return
        self._last = now
        self.clock.publish(Clock(stamp(now)))


class PerformanceMetrics:
    """~performance_metrics (gazebo_msgs/PerformanceMetrics, as Noetic's gazebo_ros publishes
    Gazebo's): the real-time factor over the last second of wall time, once a second while someone
    listens. kame's sensors have no update-rate statistics: the sensor list stays empty."""

    PERIOD = 1.0  # seconds of wall time

    def __init__(self) -> None:
        from gazebo_msgs.msg import PerformanceMetrics as Metrics

        self.metrics = topics.Publisher("~performance_metrics", Metrics, queue_size=10)
        self._since: tuple[float, float] | None = None  # (wall, simulated) when the period began

    def __call__(self, now: float) -> None:
        from gazebo_msgs.msg import PerformanceMetrics as Metrics

        wall = time.monotonic()
        if self._since is None or now < self._since[1]:
            self._since = (wall, now)
            return
        elapsed = wall - self._since[0]
        if elapsed < self.PERIOD:
            return
        factor = (now - self._since[1]) / elapsed
        self._since = (wall, now)
        if self.metrics.get_num_connections() > 0:
            msg = Metrics()
            msg.header.stamp = stamp(now)
            msg.real_time_factor = factor
            self.metrics.publish(msg)


def _number_param(name: str, default: float) -> float:
    value = process.get_param(name, default)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value < 0:
        _warn(f"Parameter {core.resolve_name(name)} must be a number of at least 0, not {value!r}: using {default}")
        return default
    return float(value)


def load_world(options: command_line.ServerOptions, env: dict[str, str]) -> World:
    resources = resources_from(env)
    seed = options.seed if options.seed is not None else 0
    try:
        path = world_file(options.world, env, SHIPPED_WORLDS)
        world = World.from_file(path, resources, seed)
    except GazeboError as exc:
        _error(f"{exc}")
        _error("The world could not be loaded: kame's gzserver runs on with an empty world")
        return World.empty(resources, seed)
    _info(f"Loaded world [{world.name}] from {path}")
    return world


def _report_options(options: command_line.ServerOptions) -> None:
    if options.physics != "ode":
        _warn(f"Physics engine [{options.physics}] asked for: kame's gzserver simulates with MuJoCo whatever -e says")
    if options.record:
        _warn("Recording (-r) is not available in kame's gzserver: the world runs unrecorded")
    if options.profile:
        _warn(f"Physics profile [{options.profile}] asked for: kame's gzserver uses the world's <physics>")
    for plugin in options.foreign_plugins():
        _warn(f"Server plugin [{plugin}] is not available in kame's gzserver: the world runs without it")
    for extra in options.ignored:
        _warn(f"Ignoring the argument [{extra}] after the world file")


def run(options: command_line.ServerOptions) -> int:
    env = dict(os.environ)
    _report_options(options)
    world = load_world(options, env)
    sim = Simulation(world, options.paused, _warn, _error, iterations=options.iterations,
                     finished=lambda: core.signal_shutdown("--iters reached"))
    host = PluginHost(sim, _info, _warn, _error)
    api: GazeboApi | None = None
    feed: ClientFeed | None = None  # what gzclient windows draw
    clock = ClockPublisher(_number_param("~pub_clock_frequency", 0.0))
    with sim.lock:
        sim.report_warnings()
        sim.add_listener(clock)
        host.start_world([plugin for plugin in world.plugins() if not plugin.model])
        for name in world.model_names():
            host.start_model(world.model_description(name), None)
        if bool(process.get_param("~enable_ros_network", True)):
            api = GazeboApi(sim, ModelFactory(sim, host, _warn))
            sim.add_listener(PerformanceMetrics())
            feed = ClientFeed(sim)
    _info("Finished loading Gazebo ROS API Plugin.")
    if options.paused:
        _info("Simulation paused: /gazebo/unpause_physics runs it")
    if feed is not None:
        feed.start()
    sim.start()
    try:
        core.wait_for_shutdown(None)
    finally:
        if feed is not None:
            feed.close()
        sim.stop()
        with sim.lock:
            host.stop_all()
            if api is not None:
                api.close()
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    try:
        options = command_line.parse(process.myargv(argv)[1:])
    except command_line.CommandLineError as exc:
        print(exc, file=sys.stderr)
        return 255
    if options.help:
        print(command_line.USAGE)
        return 0
    _log.use_roscpp_console()
    process.init_node("gazebo", argv=argv)
    try:
        return run(options)
    except KeyboardInterrupt:
        return 0
    finally:
        core.signal_shutdown("gzserver exiting")


def debug_main(argv: Sequence[str] | None = None) -> int:
    """debug (empty_world.launch debug:=true): gazebo_ros runs gzserver under gdb; kame's server is
    Python, so it runs with Python's fault handler instead, which prints every thread's stack on a crash."""
    import faulthandler

    faulthandler.enable()
    print("debug: kame's gzserver is Python: running it without gdb, with Python's fault handler on", file=sys.stderr)
    return main(argv)


def gazebo_main(argv: Sequence[str] | None = None) -> int:
    """gazebo: gzserver in this process and gzclient in its own, as Gazebo runs them; a closed window
    leaves the server running, and the window ends with the server."""
    from kame.gzclient.main import start_client

    client = start_client(list(sys.argv if argv is None else argv))
    try:
        return main(argv)
    finally:
        client.terminate()
        client.wait()
