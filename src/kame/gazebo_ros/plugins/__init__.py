"""gazebo_ros's plugins on kame, found by the file names SDF and URDF give them
(<plugin filename="libgazebo_ros_diff_drive.so">), each reading its documented parameters.

A plugin is started with its model (at load or spawn) and stopped with it (delete_model); after
each step of the world the host runs each plugin's `update` with the world locked, and each
keeps its own rate. A plugin kame does not have is named in one warning (once per file name)
and the world runs on without it.
"""

from __future__ import annotations

from collections.abc import Callable

from kame.gazebo import description as d
from kame.gazebo_ros.plugins.base import GazeboPlugin, PluginContext
from kame.gazebo_ros.plugins.body import Bumper, Imu, ImuSensor, JointStatePublisher, P3d
from kame.gazebo_ros.plugins.camera import Camera, DepthCamera
from kame.gazebo_ros.plugins.drives import DiffDrive, PlanarMove, SkidSteerDrive
from kame.gazebo_ros.plugins.kobuki import Kobuki
from kame.gazebo_ros.plugins.parameters import PluginParameterError
from kame.gazebo_ros.plugins.ray import BlockLaser, Laser, Range
from kame.gazebo_ros.simulation import Simulation

PLUGINS: dict[str, type[GazeboPlugin]] = {
    "libgazebo_ros_diff_drive.so": DiffDrive,
    "libgazebo_ros_kobuki.so": Kobuki,
    "libgazebo_ros_skid_steer_drive.so": SkidSteerDrive,
    "libgazebo_ros_planar_move.so": PlanarMove,
    "libgazebo_ros_laser.so": Laser,
    "libgazebo_ros_gpu_laser.so": Laser,
    "libgazebo_ros_ray_sensor.so": Laser,
    "libgazebo_ros_block_laser.so": BlockLaser,
    "libgazebo_ros_range.so": Range,
    "libgazebo_ros_camera.so": Camera,
    "libgazebo_ros_depth_camera.so": DepthCamera,
    "libgazebo_ros_openni_kinect.so": DepthCamera,
    "libgazebo_ros_imu.so": Imu,
    "libgazebo_ros_imu_sensor.so": ImuSensor,
    "libgazebo_ros_p3d.so": P3d,
    "libgazebo_ros_bumper.so": Bumper,
    "libgazebo_ros_joint_state_publisher.so": JointStatePublisher,
}
# gazebo_ros's own server plugins, which SDF worlds sometimes name: kame's server is both
BUILT_IN = ("libgazebo_ros_api_plugin.so", "libgazebo_ros_paths_plugin.so")


class PluginHost:
    """The running plugins of every model; its methods are called with the simulation's lock held."""

    def __init__(self, sim: Simulation, info: Callable[[str], None], warn: Callable[[str], None],
                 error: Callable[[str], None]) -> None:
        self.sim = sim
        self._info = info
        self._warn = warn
        self._error = error
        self._running: dict[str, list[GazeboPlugin]] = {}
        self._warned: set[str] = set()
        sim.add_listener(self._update)

    def start_model(self, model: d.Model, namespace: str | None) -> None:
        """Start the plugins of a model; `namespace` (spawn_model's -robot_namespace) replaces
        each plugin's <robotNamespace> when given."""
        for plugin in model.plugins:
            self._start(model.name, plugin, model, namespace)

    def start_world(self, plugins: list[d.Plugin]) -> None:
        """Start the world's own plugins (<world><plugin>)."""
        for plugin in plugins:
            self._start("", plugin, None, None)

    def _start(self, owner: str, plugin: d.Plugin, model: d.Model | None, namespace: str | None) -> None:
        kind = PLUGINS.get(plugin.filename)
        if kind is None:
            if plugin.filename not in BUILT_IN and plugin.filename not in self._warned:
                self._warned.add(plugin.filename)
                where = f"model [{owner}]" if owner else "the world"
                self._warn(f"Plugin [{plugin.name}] of {where}: kame has no {plugin.filename}; "
                           "the world runs without it")
            return
        context = PluginContext(self.sim, plugin, model, namespace, self._info, self._warn)
        try:
            started = kind(context)
        except PluginParameterError as exc:
            self._error(f"Plugin [{plugin.name}] ({plugin.filename}) of model [{owner}] not started: {exc}")
            return
        self._running.setdefault(owner, []).append(started)

    def stop_model(self, name: str) -> None:
        for plugin in self._running.pop(name, []):
            plugin.close()

    def stop_all(self) -> None:
        for name in list(self._running):
            self.stop_model(name)

    def reset(self) -> None:
        """reset_simulation and reset_world: odometry and timers start again."""
        for plugins in self._running.values():
            for plugin in plugins:
                plugin.reset()

    def _update(self, now: float) -> None:
        failed: list[tuple[str, GazeboPlugin]] = []
        for owner, plugins in self._running.items():
            for plugin in plugins:
                try:
                    plugin.update(now)
                except Exception as exc:  # whatever a plugin does wrong must not stop the world's thread
                    self._error(f"Plugin [{plugin.context.plugin.name}] ({plugin.context.plugin.filename}) of "
                                f"model [{owner}] failed and is stopped, the world runs on: {exc!r}")
                    failed.append((owner, plugin))
        for owner, plugin in failed:
            plugin.close()
            self._running[owner].remove(plugin)
