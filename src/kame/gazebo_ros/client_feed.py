"""What gzserver sends its gzclient windows (kame.gzclient.scene_message says the format): the
latched scene, sent again when a spawn or delete rebuilds the world (World.generation), and the
world's statistics five times a second (with every pose while paused), on a thread this module
owns (wall-clock paced: the world may be paused, and a paused world makes no steps to hang them
on). It also takes gzclient's step
button: /gazebo/kame/step steps a paused world so many iterations, as Gazebo's WorldControl
multi_step does."""

from __future__ import annotations

import threading
import time

from kame.client import topics
from kame.gazebo.world import World
from kame.gazebo_ros.simulation import Simulation
from kame.gzclient import scene_message as sm

STATS_PERIOD = 0.2  # seconds of wall time
MAX_STEPS = 10_000  # one press of step: Gazebo's spin box stops at 9,999 too


def scene_of(world: World) -> sm.SceneMessage:
    """The world's visuals, lights and colours as the scene message carries them; with the lock held."""
    visuals = tuple(sm.VisualMessage(v.link, v.name, v.kind, tuple(v.size), v.pose.position, v.pose.orientation,
                                     v.color, v.triangles) for v in world.visuals())
    lights = tuple(sm.LightMessage(light.name, light.type, light.pose.position, light.pose.orientation,
                                   light.diffuse, light.direction) for light in world.lights)
    return sm.SceneMessage(world.name, world.generation, world.scene.background, world.scene.ambient, lights, visuals)


class ClientFeed:
    def __init__(self, sim: Simulation) -> None:
        from std_msgs.msg import String, UInt32

        self._sim = sim
        self._scene = topics.Publisher(sm.SCENE_TOPIC, String, queue_size=1, latch=True)
        self._stats = topics.Publisher(sm.STATS_TOPIC, String, queue_size=1)
        self._step = topics.Subscriber(sm.STEP_TOPIC, UInt32, self._on_step, queue_size=10)
        self._sent_generation: int | None = None
        self._started = time.monotonic()  # Gazebo's real time: wall time since the world (re)started
        self._last_sim_time = 0.0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="gzserver-client-feed", daemon=True)

    def start(self) -> None:
        self._send()
        self._thread.start()

    def close(self) -> None:
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join()
        self._step.unregister()
        self._stats.unregister()
        self._scene.unregister()

    def _run(self) -> None:
        while not self._stop.wait(STATS_PERIOD):
            self._send()

    def _send(self) -> None:
        from std_msgs.msg import String

        with self._sim.lock:
            world = self._sim.world
            scene = scene_of(world) if world.generation != self._sent_generation else None
            now = world.sim_time
            if now < self._last_sim_time:  # reset_simulation: real time starts again with sim time
                self._started = time.monotonic()
            self._last_sim_time = now
            links = models = None
            if self._sim.paused:  # no steps, so no link_states: the poses come with the stats
                links = {name: (state.pose.position, state.pose.orientation)
                         for name, state in world.link_states().items()}
                models = {name: (state.pose.position, state.pose.orientation)
                          for name, state in world.model_states().items()}
            stats = sm.WorldStats(now, time.monotonic() - self._started, world.iterations, self._sim.paused,
                                  links, models)
        if scene is not None:
            self._scene.publish(String(sm.encode_scene(scene)))
            self._sent_generation = scene.generation
        if self._stats.get_num_connections() > 0:
            self._stats.publish(String(sm.encode_stats(stats)))

    def _on_step(self, msg: object) -> None:
        count = min(MAX_STEPS, int(getattr(msg, "data", 0)))
        for _ in range(count):
            if not self._sim.paused:  # running: the world's own thread steps it
                return
            self._sim.step()
