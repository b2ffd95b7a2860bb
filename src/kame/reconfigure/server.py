"""dynamic_reconfigure's Server on kame.client: a node's parameters, changed while it runs.

Server(ConfigType, callback) reads the parameters from the parameter server (falling back to
the cfg's defaults), clamps them to min/max, calls callback(config, level=~0), then keeps
~parameter_descriptions and ~parameter_updates latched and answers ~set_parameters; every
accepted configuration is written back to the parameter server.
"""

from __future__ import annotations

import copy
import threading
from collections.abc import Callable
from typing import Any

from dynamic_reconfigure.msg import Config as ConfigMsg
from dynamic_reconfigure.msg import ConfigDescription as ConfigDescrMsg
from dynamic_reconfigure.srv import Reconfigure
from kame.client import log
from kame.client.process import get_param, set_param
from kame.client.services import Service
from kame.client.topics import Publisher
from kame.reconfigure.encoding import (
    Config,
    decode_config,
    encode_config,
    encode_description,
    extract_params,
    get_tree,
    initial_config,
)
from kame.reconfigure.errors import DynamicReconfigureCallbackException


def server_namespace(namespace: str) -> str:
    if not namespace:
        return "~"
    if namespace[0] not in "/~":
        namespace = "~" + namespace
    return (namespace + "/").replace("//", "/")


class Server:
    """Serve a generated <Name>Config type: `Server(TutorialsConfig, callback)`."""

    def __init__(self, type: Any, callback: Callable[[Config, int], Any], namespace: str = "") -> None:
        self.mutex = threading.Lock()
        self.ns = server_namespace(namespace)
        self.type = type
        self.params = extract_params(type.config_description)
        self.description = encode_description(type)
        config = Config(type.defaults)
        for param in self.params:
            value = get_param(self.ns + param["name"], None)
            if value is not None:
                config[param["name"]] = value
        self.callback = callback
        self._clamp(config)
        config["groups"] = get_tree(self.description)
        self.config = initial_config(encode_config(config), type.config_description)
        self.descr_topic = Publisher(self.ns + "parameter_descriptions", ConfigDescrMsg, latch=True, queue_size=10)
        self.descr_topic.publish(self.description)
        self.update_topic = Publisher(self.ns + "parameter_updates", ConfigMsg, latch=True, queue_size=10)
        self._change_config(self.config, ~0)  # as the C++ server: the first call has every level bit set
        self.set_service = Service(self.ns + "set_parameters", Reconfigure, self._set_callback)

    def update_configuration(self, changes: dict[str, Any]) -> Config:
        """Apply changes (clamped) as if a client had sent them; returns the configuration the callback kept."""
        with self.mutex:
            new_config = copy.deepcopy(self.config)
            new_config.update(changes)
            self._clamp(new_config)
            return self._change_config(new_config, self._calc_level(new_config, self.config))

    def _change_config(self, config: Config, level: int) -> Config:
        accepted = self.callback(config, level)
        if accepted is None:
            message = "Reconfigure callback should return a possibly updated configuration."
            log.emit(log.ERROR, "%s", (message,))
            raise DynamicReconfigureCallbackException(message)
        self.config = accepted
        for param in self.params:
            set_param(self.ns + param["name"], self.config[param["name"]])
        self.update_topic.publish(encode_config(self.config))
        return self.config

    def _calc_level(self, new: Config, old: Config) -> int:
        level = 0
        for param in self.params:
            if new[param["name"]] != old[param["name"]]:
                level |= param["level"]
        return level

    def _clamp(self, config: Config) -> None:
        for param in self.params:
            name = param["name"]
            highest, lowest, value = self.type.max[name], self.type.min[name], config[name]
            if highest != "" and value > highest:
                config[name] = highest
            elif lowest != "" and value < lowest:
                config[name] = lowest

    def _set_callback(self, request: Any) -> Any:
        return encode_config(self.update_configuration(decode_config(request.config, self.type.config_description)))
