"""roslaunch.netapi: the roslaunch servers announced on the master (/roslaunch/uris) and the
processes each one reports (list_processes)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import rosgraph
import rosgraph.network
from kame.net.server_proxy import ServerProxy

__all__ = ["NetProcess", "ServerProxy", "get_roslaunch_uris", "list_processes"]

_ID = "/roslaunch_netapi"


def get_roslaunch_uris() -> list[str] | None:
    """The URIs of the roslaunch servers of the current master; None when it cannot be asked."""
    try:
        return list(rosgraph.Master(_ID).getParam("/roslaunch/uris").values())
    except rosgraph.MasterException:
        return None


class NetProcess:
    """A process as a roslaunch server reports it."""

    def __init__(self, name: str, respawn_count: int, is_alive: bool, roslaunch_uri: str) -> None:
        self.is_alive = is_alive
        self.respawn_count = respawn_count
        self.name = name
        self.roslaunch_uri = roslaunch_uri
        self.machine, _ = rosgraph.network.parse_http_host_and_port(roslaunch_uri)


def list_processes(roslaunch_uris: Sequence[str] | None = None) -> list[NetProcess]:
    """The processes of each server (all the master knows of unless given); one that does not answer is skipped."""
    uris = list(roslaunch_uris or get_roslaunch_uris() or [])
    procs: list[NetProcess] = []
    for uri in uris:
        try:
            reply: Any = ServerProxy(uri).list_processes()
            code, _, val = reply
        except Exception:  # as ROS: a server gone away lists nothing
            continue
        if code == 1:
            active, dead = val
            procs += [NetProcess(a[0], a[1], True, uri) for a in active]
            procs += [NetProcess(d[0], d[1], False, uri) for d in dead]
    return procs
