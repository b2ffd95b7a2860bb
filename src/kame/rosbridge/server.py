"""rosbridge_server's rosbridge_websocket: the node that serves the rosbridge v2 protocol.

`rosrun rosbridge_server rosbridge_websocket` or `roslaunch rosbridge_server
rosbridge_websocket.launch`. Private parameters, as rosbridge's: ~port (9090; 0 picks a free
one, published as ~actual_port), ~address ("" or 0.0.0.0: every interface, as rosbridge
listens), ~ssl with ~certfile and ~keyfile (wss://), ~max_message_size (the largest frame a
client may send; "None" is kame's bound, 10 MiB), ~topics_glob and ~services_glob; kame's own:
~max_queue_frames and ~max_queue_bytes, each client's bound of frames waiting to go out.
~authenticate: each client's first op must be rosauth's auth, checked by the /authenticate
service (rosauth's ros_mac_authentication; kame.rosbridge.auth). ~bson_only_mode (BSON) is not
kame's: asked for, the node says so and stops rather than serve clients set up for it.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from kame.client import log
from kame.client.process import get_param, init_node, set_param, spin
from kame.net.websocket_listener import Client, Limits, WebSocketListener
from kame.rosbridge import globs
from kame.rosbridge.graph import Graph
from kame.rosbridge.session import Session, Shared
from kame.rosbridge.topics import Latest, Pacer

DEFAULT_PORT = 9090
CALL_WORKERS = 8  # call_service ops in progress at once, over all clients


def _number(value: Any, default: int) -> int:
    if value is None or str(value).strip() in ("", "None", "none"):
        return default
    return int(value)


def _flag(value: Any) -> bool:
    return value is True or str(value).strip().lower() in ("true", "1", "yes")


class Bridge:
    """The listener and what its clients share; `close()` ends every client and thread."""

    def __init__(self, address: str, port: int, limits: Limits, tls: tuple[str, str] | None,
                 topics_glob: tuple[str, ...] | None = None, services_glob: tuple[str, ...] | None = None,
                 authenticate: bool = False) -> None:
        self.shared = Shared(Graph(), Latest(), Pacer(), ThreadPoolExecutor(CALL_WORKERS, "kame-rosbridge-call"),
                             limits.max_message_size, topics_glob, services_glob, authenticate)
        try:
            self.listener = WebSocketListener("" if address == "0.0.0.0" else address, port, self._open,
                                              limits=limits, tls=tls, where="rosbridge websocket server")
        except BaseException:
            self.shared.pacer.close()
            self.shared.workers.shutdown()
            raise
        self.port = self.listener.port

    def _open(self, client: Client) -> Session:
        log.emit(log.INFO, "Client connected. %d clients total.", (len(self.listener.clients()),))
        if self.shared.authenticate:
            log.emit(log.INFO, "Awaiting proper authentication...", ())
        return _Logged(self.shared, client, self.listener)

    def start(self) -> None:
        self.listener.start()

    def close(self) -> None:
        self.listener.close()
        self.shared.workers.shutdown(cancel_futures=True)
        self.shared.pacer.close()


class _Logged(Session):
    def __init__(self, shared: Shared, client: Client, listener: WebSocketListener) -> None:
        super().__init__(shared, client.send, client.peer, client.close)
        self._listener = listener
        self._client = client

    def on_close(self) -> None:
        super().on_close()
        # past its queue's bound (~max_queue_frames, ~max_queue_bytes) a client loses its oldest frames
        log.emit(log.INFO, "Client disconnected. %d clients total. %d frames sent to it, %d dropped.",
                 (len(self._listener.clients()), self._client.sent, self._client.dropped))


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    init_node("rosbridge_websocket", argv)
    if _flag(get_param("~bson_only_mode", False)):
        log.emit(log.FATAL, "~bson_only_mode: kame's bridge speaks JSON and CBOR, not BSON; refusing to serve "
                 "clients that were set up for BSON only", ())
        return 1
    port = _number(get_param("~port", DEFAULT_PORT), DEFAULT_PORT)
    address = str(get_param("~address", "") or "")
    tls = None
    if _flag(get_param("~ssl", False)):
        tls = (str(get_param("~certfile", "")), str(get_param("~keyfile", "")))
    defaults = Limits()
    limits = Limits(max_message_size=_number(get_param("~max_message_size", None), defaults.max_message_size),
                    max_frames=_number(get_param("~max_queue_frames", None), defaults.max_frames),
                    max_bytes=_number(get_param("~max_queue_bytes", None), defaults.max_bytes))
    try:
        bridge = Bridge(address, port, limits, tls, globs.parse(get_param("~topics_glob", None)),
                        globs.parse(get_param("~services_glob", None)), _flag(get_param("~authenticate", False)))
    except OSError as exc:
        log.emit(log.FATAL, "Unable to start the rosbridge WebSocket server on %s:%s: %s", (address, port, exc))
        return 1
    set_param("~actual_port", bridge.port)
    bridge.start()
    scheme = "wss" if tls else "ws"
    log.emit(log.INFO, "Rosbridge WebSocket server started at %s://%s:%d", (scheme, address or "0.0.0.0", bridge.port))
    try:
        spin()
    finally:
        bridge.close()
    return 0
