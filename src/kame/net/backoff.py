"""How long to wait before starting again what keeps dying young: a respawning program
(kame.net.process, the launch supervisor) or a connection to a publisher that keeps dropping
us (kame.node.publisher_link). Pure arithmetic on the lifetimes it is told: no clock here."""

from __future__ import annotations


class RespawnBackoff:
    """How long a respawning child waits before its next start, or a subscriber before it
    connects again to a publisher that dropped it.

    A child (a connection) that dies within YOUNG seconds of its start died young; from the
    second young death in a row on, it waits START, doubled per further one, up to CAP (or the
    configured delay if that is longer). One that lived longer starts the count afresh."""

    YOUNG = 5.0
    START = 0.5
    CAP = 30.0

    def __init__(self) -> None:
        self.young_deaths = 0  # in a row
        self.backoff = 0.0  # the last backoff returned as news

    def delay(self, lived: float, configured: float) -> tuple[float, bool]:
        """(seconds to wait, whether that is a new backoff step worth saying once)."""
        self.young_deaths = self.young_deaths + 1 if lived < self.YOUNG else 0
        if self.young_deaths < 2:
            self.backoff = 0.0
            return configured, False
        backoff = min(self.CAP, self.START * 2.0 ** (self.young_deaths - 2))
        if backoff <= configured:
            return configured, False
        news = backoff != self.backoff
        self.backoff = backoff
        return backoff, news
