"""rqt_reconfigure's talk with ROS, on the tool's own Node: the servers the master knows, one
followed server's latched parameter_descriptions and parameter_updates (newest kept; `changed`
is called from the subscription's thread), and changes sent through its set_parameters service
(with a timeout; the window calls it from its worker thread).
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Mapping
from typing import Any

from dynamic_reconfigure.msg import Config as ConfigMsg
from dynamic_reconfigure.msg import ConfigDescription as ConfigDescrMsg
from dynamic_reconfigure.srv import Reconfigure, ReconfigureRequest, ReconfigureResponse
from kame.msg.errors import MessageError
from kame.node.master_proxy import MasterError
from kame.node.node import Node
from kame.node.services import ServiceError
from kame.node.topics import serialize_payload
from kame.protocol.xmlrpc import XmlRpcError
from kame.reconfigure.encoding import decode_config, decode_description, encode_config
from kame.rqt.reconfigure_model import SET_PARAMETERS, servers

CALL_TIMEOUT = 5.0


class ReconfigureError(Exception):
    """The server is gone, hung, or answered what is no configuration."""


class ReconfigureSource:
    def __init__(self, node: Node, changed: Callable[[str], None], timeout: float = CALL_TIMEOUT) -> None:
        self.node = node
        self.timeout = timeout
        self._changed = changed
        self._lock = threading.Lock()
        self.server = ""
        self._description: dict[str, Any] | None = None
        self._config: dict[str, Any] | None = None

    def servers(self) -> list[str]:
        return servers(str(name) for name, _ in self.node.master.call("getSystemState")[2])

    def follow(self, server: str) -> None:
        """Follow `server`'s description and configuration (the ones before are forgotten)."""
        self.stop()
        with self._lock:
            self.server = server
        self.node.subscribe(server + "/parameter_descriptions", ConfigDescrMsg._type, ConfigDescrMsg._md5sum,
                            ConfigDescrMsg._full_text, lambda frames, _h: self._deliver(server, frames, True))
        self.node.subscribe(server + "/parameter_updates", ConfigMsg._type, ConfigMsg._md5sum, ConfigMsg._full_text,
                            lambda frames, _h: self._deliver(server, frames, False))

    def _deliver(self, server: str, frames: list[memoryview], is_description: bool) -> None:
        if not frames:
            return
        try:
            if is_description:
                decoded = decode_description(ConfigDescrMsg().deserialize(bytes(frames[-1])))
            else:
                decoded = dict(decode_config(ConfigMsg().deserialize(bytes(frames[-1]))))
        except (MessageError, KeyError, StopIteration):
            return  # a server's malformed message: the newest good one stays
        with self._lock:
            if server != self.server:
                return
            if is_description:
                self._description = decoded
            else:
                self._config = decoded
        self._changed(server)

    def state(self) -> tuple[dict[str, Any] | None, dict[str, Any] | None]:
        """The followed server's newest description tree and configuration (None until they come)."""
        with self._lock:
            return self._description, self._config

    def set(self, changes: Mapping[str, Any]) -> dict[str, Any]:
        """Send `changes` (typed values) to the followed server; the configuration it kept."""
        server = self.server
        client = self.node.service_client(server + SET_PARAMETERS, Reconfigure._type, Reconfigure._md5sum)
        try:
            answer = client.call(serialize_payload(ReconfigureRequest(encode_config(dict(changes)))),
                                 timeout=self.timeout)
            return dict(decode_config(ReconfigureResponse().deserialize(answer).config))
        except (OSError, ServiceError, MasterError, XmlRpcError, MessageError) as exc:
            raise ReconfigureError(f"{server}: {exc}") from exc
        finally:
            client.close()

    def stop(self) -> None:
        with self._lock:
            server, self.server = self.server, ""
            self._description = self._config = None
        if server:
            self.node.unsubscribe(server + "/parameter_descriptions")
            self.node.unsubscribe(server + "/parameter_updates")
