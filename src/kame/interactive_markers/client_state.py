"""What a client of interactive markers (rviz's InteractiveMarkers display) does with a
server's update_full and update topics (ROS 1, 1.12), without I/O: a server's updates wait
until its InteractiveMarkerInit arrives; the init's markers are the state at its sequence
number and the waiting updates after it apply in order; then every UPDATE must carry the next
number and a KEEP_ALIVE the current one. A gap (an update missed) drops the server's state
until an init at least as new (the server publishes one with every change: the newest
received is kept for this)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

KEEP_ALIVE, UPDATE = 0, 1
WAITING_UPDATES = 100  # updates kept per server while its init has not come


@dataclass
class ServerSync:
    seq_num: int | None = None  # None: waiting for an init
    waiting: list[Any] = field(default_factory=list)
    newest_init: Any = None


class ClientState:
    def __init__(self) -> None:
        self.servers: dict[str, ServerSync] = {}
        self.markers: dict[tuple[str, str], Any] = {}  # (server_id, name) -> InteractiveMarker
        self.version = 0  # counts changes to `markers`
        self.problem = ""  # the last gap seen, for the display's status

    def reset(self) -> None:
        self.servers, self.markers, self.problem = {}, {}, ""
        self.version += 1

    def init(self, message: Any) -> None:
        server = self.servers.setdefault(message.server_id, ServerSync())
        if server.newest_init is None or message.seq_num >= server.newest_init.seq_num:
            server.newest_init = message
        if server.seq_num is None:
            self._start(message.server_id, server)

    def _start(self, server_id: str, server: ServerSync) -> None:
        init = server.newest_init
        if init is None:
            return
        for key in [key for key in self.markers if key[0] == server_id]:
            del self.markers[key]
        for marker in init.markers:
            self.markers[(server_id, marker.name)] = marker
        server.seq_num = init.seq_num
        self.version += 1
        waiting, server.waiting = server.waiting, []
        for update in waiting:
            if update.seq_num > init.seq_num:
                self.update(update)

    def update(self, message: Any) -> None:
        server = self.servers.setdefault(message.server_id, ServerSync())
        if server.seq_num is None:
            server.waiting = [*server.waiting, message][-WAITING_UPDATES:]
            return
        if message.type == KEEP_ALIVE:
            if message.seq_num > server.seq_num:
                self._gap(message.server_id, server, message)
            return
        if message.seq_num <= server.seq_num:  # older than the init it follows
            return
        if message.seq_num != server.seq_num + 1:
            self._gap(message.server_id, server, message)
            return
        server.seq_num = message.seq_num
        for marker in message.markers:
            self.markers[(message.server_id, marker.name)] = marker
        for pose in message.poses:
            marker = self.markers.get((message.server_id, pose.name))
            if marker is not None:
                marker.pose, marker.header = pose.pose, pose.header
        for name in message.erases:
            self.markers.pop((message.server_id, name), None)
        self.version += 1

    def _gap(self, server_id: str, server: ServerSync, message: Any) -> None:
        self.problem = f"server {server_id}: expected update {(server.seq_num or 0) + 1}, got {message.seq_num}" \
                       "; waiting for a new init"
        server.seq_num = None
        if message.type == UPDATE:
            server.waiting.append(message)
        needed = message.seq_num - 1 if message.type == UPDATE else message.seq_num
        if server.newest_init is not None and server.newest_init.seq_num >= needed:
            self._start(server_id, server)
