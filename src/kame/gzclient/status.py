"""gzclient's status bar as text: Real Time Factor, Sim Time, Real Time, Iterations, in Gazebo's
words and formats (times as "DD HH:MM:SS.mmm"). The factor is simulated over wall time across the
last second of statistics, as Gazebo's window averages it."""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

from kame.gzclient.scene_message import WorldStats

FACTOR_WINDOW = 1.0  # seconds of real time


def gazebo_time(seconds: float) -> str:
    milliseconds = round(max(0.0, seconds) * 1000)
    days, rest = divmod(milliseconds, 86_400_000)
    hours, rest = divmod(rest, 3_600_000)
    minutes, rest = divmod(rest, 60_000)
    whole, millis = divmod(rest, 1000)
    return f"{days:02d} {hours:02d}:{minutes:02d}:{whole:02d}.{millis:03d}"


@dataclass
class StatusFigures:
    latest: WorldStats | None = None
    _samples: deque[WorldStats] = field(default_factory=deque)

    def update(self, stats: WorldStats) -> None:
        if self.latest is not None and stats.sim_time < self.latest.sim_time:  # reset: a new history
            self._samples.clear()
        self.latest = stats
        self._samples.append(stats)
        while len(self._samples) > 2 and stats.real_time - self._samples[1].real_time >= FACTOR_WINDOW:
            self._samples.popleft()

    @property
    def real_time_factor(self) -> float:
        if len(self._samples) < 2:
            return 0.0
        first, last = self._samples[0], self._samples[-1]
        elapsed = last.real_time - first.real_time
        return (last.sim_time - first.sim_time) / elapsed if elapsed > 0 else 0.0

    @property
    def paused(self) -> bool:
        return self.latest is not None and self.latest.paused

    def fields(self) -> list[str]:
        """The status bar's labels, left to right."""
        if self.latest is None:
            return ["Waiting for gzserver (/gazebo/kame/world_stats)"]
        return [f"Real Time Factor: {self.real_time_factor:.2f}", f"Sim Time: {gazebo_time(self.latest.sim_time)}",
                f"Real Time: {gazebo_time(self.latest.real_time)}", f"Iterations: {self.latest.iterations}"]
