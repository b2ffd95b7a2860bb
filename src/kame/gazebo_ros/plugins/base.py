"""What every plugin has: its description, its model, its namespace, its clock and its topics."""

from __future__ import annotations

import abc
import math
from collections.abc import Callable
from typing import Any

from kame.client import topics
from kame.gazebo import description as d
from kame.gazebo_ros.plugins.parameters import GAZEBO_ROS_MISSING, Parameters, PluginParameterError
from kame.gazebo_ros.simulation import Simulation


def topic_name(namespace: str, name: str) -> str:
    """A plugin's topic: absolute as given, else under the robot namespace (gazebo_ros's plugins
    make their NodeHandle in it), never under the server's own /gazebo."""
    if name.startswith("/"):
        return name
    return f"/{namespace}/{name}" if namespace else f"/{name}"


class Every:
    """A rate in simulated time: due at most `rate` times a second (0: at every step); time that
    goes back (a reset) starts it again."""

    def __init__(self, rate: float) -> None:
        self.period = 1.0 / rate if rate > 0 else 0.0
        self._last = -math.inf

    def due(self, now: float) -> bool:
        if now < self._last:
            self._last = -math.inf
        if now - self._last + 1e-9 < self.period:
            return False
        self._last = now
        return True

    def restart(self) -> None:
        self._last = -math.inf


class PluginContext:
    """The world and the ROS side a plugin is started with."""

    def __init__(self, sim: Simulation, plugin: d.Plugin, model: d.Model | None, namespace: str | None,
                 info: Callable[[str], None], warn: Callable[[str], None]) -> None:
        self.sim = sim
        self.plugin = plugin
        self.model = model
        self._namespace = namespace
        self.info = info
        self.warn = warn

    @property
    def world(self) -> Any:
        return self.sim.world

    def parameters(self, info: str, missing: str = GAZEBO_ROS_MISSING) -> Parameters:
        return Parameters(self.plugin, info, missing)

    def namespace(self, parameters: Parameters) -> str:
        """spawn_model's -robot_namespace when given, else the plugin's <robotNamespace>."""
        return self._namespace if self._namespace is not None else parameters.namespace()

    def model_name(self) -> str:
        return self.model.name if self.model is not None else ""

    def scoped(self, name: str) -> str:
        """A link or joint of the plugin's model, as the world names it (model::name)."""
        return f"{self.model_name()}::{name}"

    def sensor(self) -> d.Sensor | None:
        if self.model is None or not self.plugin.sensor:
            return None
        link = self.model.link(self.plugin.link)
        if link is None:
            return None
        return next((s for s in link.sensors if s.name == self.plugin.sensor), None)

    def sensor_info(self) -> Any:
        """The World's SensorInfo of the plugin's sensor, which its sensor readings take."""
        link = self.scoped(self.plugin.link)
        found = next((s for s in self.world.sensors() if s.link == link and s.name == self.plugin.sensor), None)
        if found is None:
            raise PluginParameterError(f"plugin [{self.plugin.name}] names sensor [{self.plugin.sensor}] of "
                                       f"[{link}], which the world does not have")
        return found

    def publisher(self, namespace: str, name: str, data_class: type[Any], latch: bool = False) -> topics.Publisher:
        return topics.Publisher(topic_name(namespace, name), data_class, queue_size=10, latch=latch)

    def subscriber(self, namespace: str, name: str, data_class: type[Any],
                   callback: Callable[[Any], None]) -> topics.Subscriber:
        return topics.Subscriber(topic_name(namespace, name), data_class, callback, queue_size=1)

    def report(self, parameters: Parameters) -> None:
        for note in parameters.notes:
            self.warn(note)


class GazeboPlugin(abc.ABC):
    """A running plugin: `update` after each step (the world locked), `reset` on reset_world and
    reset_simulation, `close` when its model goes."""

    def __init__(self, context: PluginContext) -> None:
        self.context = context
        self._topics: list[topics.Publisher | topics.Subscriber] = []

    def own(self, topic: Any) -> Any:
        """Keep a publisher or subscriber, to be unregistered by `close`."""
        self._topics.append(topic)
        return topic

    @abc.abstractmethod
    def update(self, now: float) -> None:
        """After each step of the world, with the world locked."""

    def reset(self) -> None:  # noqa: B027 (a hook: most plugins keep no state across a reset)
        """reset_world and reset_simulation: start again what counts time or integrates motion."""

    def close(self) -> None:
        for topic in self._topics:
            topic.unregister()
        self._topics.clear()
