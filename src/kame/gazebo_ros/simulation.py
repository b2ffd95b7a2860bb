"""The running world of gzserver: kame.gazebo's World, the lock every ROS callback takes to touch
it, and the thread that steps it (owned here: `start` makes it, `stop` ends and joins it). The
World's cameras render on that thread, so it also frees them when it ends.

Pacing: each step is max_step_size of simulated time; with a real_time_factor f > 0 the thread
waits until f x wall time has caught up (a late step is not made up for by a burst); with f = 0,
or a real_time_update_rate (gazebo_ros's max_update_rate) of 0, it steps as fast as it can. A
paused world waits on its condition until unpause or stop. After each step the listeners run, in
order, with the world locked: the publishers and plugins. What the World put right (a diverging
model reset) is logged as a warning.
"""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Callable

from kame.gazebo.world import World

StepListener = Callable[[float], None]  # called with the simulated time after each step


class Simulation:
    def __init__(self, world: World, paused: bool, warn: Callable[[str], None], error: Callable[[str], None],
                 iterations: int | None = None, finished: Callable[[], None] | None = None) -> None:
        self.world = world
        self.lock = threading.RLock()
        self._changed = threading.Condition(self.lock)
        self._paused = paused
        self._stopping = False
        self._warn = warn
        self._error = error
        self._failed: list[StepListener] = []  # listeners that failed once: said, not said again
        self._iterations_left = iterations
        self._finished = finished
        self._listeners: list[StepListener] = []
        self._thread: threading.Thread | None = None
    # ------------------------------------------------------------------ control

    @property
    def paused(self) -> bool:
        return self._paused

    def set_paused(self, paused: bool) -> None:
        with self._changed:
            self._paused = paused
            self._changed.notify_all()

    def add_listener(self, listener: StepListener) -> None:
        with self.lock:
            self._listeners.append(listener)

    def remove_listener(self, listener: StepListener) -> None:
        with self.lock:
            if listener in self._listeners:
                self._listeners.remove(listener)

    def start(self) -> None:
        self._thread = threading.Thread(target=self._run, name="gzserver-physics", daemon=True)
        self._thread.start()

    def stop(self) -> None:
        with self._changed:
            self._stopping = True
            self._changed.notify_all()
        if self._thread is not None and self._thread is not threading.current_thread():
            self._thread.join()

    # ------------------------------------------------------------------ stepping

    def report_warnings(self) -> None:
        """Log what the World left out or put right since the last call; with the lock held."""
        for warning in self.world.take_warnings():
            self._warn(warning)

    def step(self) -> float:
        """One step and its listeners; the world's time after it. The caller holds no lock. A step
        the World cannot make pauses the simulation with an error line; a listener that fails says
        so once and is called again at the next step (the world's thread never ends on an error)."""
        with self.lock:
            try:
                self.world.step()
            except Exception as exc:  # whatever stops MuJoCo must leave the node answering
                self._error(f"The world could not be stepped at {self.world.sim_time:.3f} s ({exc!r}): "
                            "the simulation is paused")
                self.set_paused(True)
                return self.world.sim_time
            self.report_warnings()
            now = self.world.sim_time
            for listener in list(self._listeners):
                try:
                    listener(now)
                except Exception as exc:  # a publisher's failure must not stop the world's thread
                    if listener not in self._failed:
                        self._failed.append(listener)
                        self._error(f"After a step, {listener!r} failed ({exc!r}); the simulation runs on")
        return now

    def _wait_while_paused(self) -> bool:
        """False once stopping."""
        with self._changed:
            while not self._stopping and self._paused:
                self._changed.wait()
            return not self._stopping

    def _pace(self, started_wall: float, started_sim: float, now: float) -> tuple[float, float]:
        """Wait until wall time matches the simulated time at the real-time factor; the new
        reference (wall, sim) when the world ran late or was paused."""
        physics = self.world.physics
        factor = physics.real_time_factor
        # a max_update_rate (real_time_update_rate) of 0 runs unthrottled, as in Gazebo
        if physics.real_time_update_rate == 0 or not (factor > 0 and math.isfinite(factor)):
            return started_wall, started_sim
        due = started_wall + (now - started_sim) / factor
        delay = due - time.monotonic()
        if delay < -0.1:  # late (or just unpaused): take now as the new start, no burst
            return time.monotonic(), now
        if delay > 0:
            with self._changed:
                self._changed.wait_for(lambda: self._stopping or self._paused, timeout=delay)
        return started_wall, started_sim

    def _run(self) -> None:
        try:
            self._step_until_stopped()
        finally:
            with self.lock:  # the cameras' GL contexts were made current here: they are freed here
                self.world.close()

    def _step_until_stopped(self) -> None:
        wall, sim = time.monotonic(), self.world.sim_time
        while self._wait_while_paused():
            now = self.step()
            if self._iterations_left is not None:
                self._iterations_left -= 1
                if self._iterations_left <= 0:
                    if self._finished is not None:
                        self._finished()
                    return
            wall, sim = self._pace(wall, sim, now)  # after a pause it runs late: the pace starts again
