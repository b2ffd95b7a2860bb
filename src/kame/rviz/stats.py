"""How well rviz's window keeps up, as `rviz --stats` prints it each second: the frames it drew
and showed, the turns of its frame timer, and the longest time between two turns (the window's
event loop was busy that long: a message it took too long over stalls the view as long)."""

from __future__ import annotations


class FrameStats:
    def __init__(self, now: float) -> None:
        self.since = now  # the start of what the next report counts
        self.drawn = 0
        self.turns = 0
        self.longest_gap = 0.0
        self.last_turn = now

    def frame_shown(self) -> None:
        self.drawn += 1

    def turned(self, now: float) -> None:
        self.longest_gap = max(self.longest_gap, now - self.last_turn)
        self.last_turn = now
        self.turns += 1

    def report(self, now: float) -> str:
        """One line on what happened since the last report, and a fresh count from `now`."""
        span = max(now - self.since, 1e-9)
        gap = max(self.longest_gap, now - self.last_turn)  # a stall going on now counts too
        line = (f"rviz stats: {self.drawn / span:.1f} frames/s drawn, {self.turns / span:.1f} turns/s, "
                f"longest gap {gap * 1000:.0f} ms")
        self.since, self.drawn, self.turns, self.longest_gap = now, 0, 0, 0.0
        return line
