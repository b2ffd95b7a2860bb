"""Why a publisher's advertised address cannot be reached from here, and the one line that says so.

The classic several-machines failure: a node advertises a name (its host name, or ROS_HOSTNAME)
or an address (ROS_IP) that the subscriber's machine cannot resolve or reach. The topic shows
in `rostopic list` but no data flows. A subscriber says it once per publisher, naming the
publisher, what it advertised and the fix, instead of retrying silently.

One refusal is no address problem: a publisher on this machine whose node API refuses the
connection has no process listening there any more. It died without unregistering (SIGKILL,
a crash), and its registration is stale; the line says that instead.
"""

from __future__ import annotations

import threading


def unreachable_message(publisher: str | None, topic: str, advertised: str, reason: str) -> str:
    who = f"publisher {publisher}" if publisher else "a publisher"
    return (f"cannot reach {who} of {topic} at {advertised}: {reason}. Its machine advertises an address "
            f"this machine cannot use: start it with ROS_IP set to its IP address, or ROS_HOSTNAME set to a "
            f"name that resolves to it here (and check firewalls between the machines)")


def dead_publisher_message(publisher: str | None, topic: str, advertised: str) -> str:
    who = f"publisher {publisher}" if publisher else "a publisher"
    return (f"{who} of {topic} is dead: nothing listens at {advertised} on this machine any more, so its "
            f"process ended without unregistering (killed, or crashed); the master lists it until "
            f"`rosnode cleanup` removes it or it starts again")


class ReportedOnce:
    """Keys (publisher URIs) already reported, so that retries do not repeat the line."""

    def __init__(self) -> None:
        self._seen: set[str] = set()
        self._lock = threading.Lock()

    def first(self, key: str) -> bool:
        with self._lock:
            if key in self._seen:
                return False
            self._seen.add(key)
            return True
