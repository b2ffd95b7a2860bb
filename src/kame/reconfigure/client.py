"""dynamic_reconfigure's Client on kame.client: read and change a running server's configuration.

Client(name, timeout, config_callback) waits for <name>/set_parameters, then follows the
latched <name>/parameter_descriptions and <name>/parameter_updates topics.
update_configuration converts values as dynparam's users type them ("true", enum constant
names, numbers as text) to the parameter's type before sending (encoding.converted).
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Callable
from typing import Any

from dynamic_reconfigure.msg import Config as ConfigMsg
from dynamic_reconfigure.msg import ConfigDescription as ConfigDescrMsg
from dynamic_reconfigure.srv import Reconfigure
from kame.client import core
from kame.client.errors import ROSException
from kame.client.services import ServiceException, ServiceProxy, wait_for_service
from kame.client.topics import Subscriber
from kame.reconfigure.encoding import (
    Config,
    converted,
    decode_config,
    decode_description,
    encode_config,
    extract_params,
)
from kame.reconfigure.errors import DynamicReconfigureCallbackException, DynamicReconfigureParameterException


class Client:
    """`Client("/node", timeout=30, config_callback=f)`: a running dynamic_reconfigure server's configuration."""

    def __init__(self, name: str, timeout: float | None = None,
                 config_callback: Callable[[Config], Any] | None = None,
                 description_callback: Callable[[list[dict[str, Any]]], Any] | None = None) -> None:
        self.name = name
        self.config: Config | None = None
        self.param_description: list[dict[str, Any]] | None = None
        self.group_description: dict[str, Any] | None = None
        self._config_received = threading.Event()
        self._description_received = threading.Event()
        self._config_callback = config_callback
        self._description_callback = description_callback
        service = core.resolve_name(name + "/set_parameters")
        if not timeout:
            try:
                wait_for_service(service, 1.0)
            except ROSException:
                print(f"Waiting for service {service}...", file=sys.stderr)
                wait_for_service(service, None)
        else:
            wait_for_service(service, timeout)
        self._set_service = ServiceProxy(service, Reconfigure)
        self._descriptions_sub = Subscriber(core.resolve_name(name + "/parameter_descriptions"), ConfigDescrMsg,
                                            self._descriptions_msg)
        self._updates_sub = Subscriber(core.resolve_name(name + "/parameter_updates"), ConfigMsg, self._updates_msg)

    @staticmethod
    def _wait(event: threading.Event, timeout: float | None) -> None:
        with core.woken_at_shutdown(event):
            event.wait(timeout or None)

    def get_configuration(self, timeout: float | None = None) -> Config | None:
        """The server's latest configuration, waiting up to `timeout` (None: until it comes) for the first."""
        if not timeout and not self._config_received.is_set():
            self._wait(self._config_received, 1.0)
            if self.config is None:
                print("Waiting for configuration...", file=sys.stderr)
        self._wait(self._config_received, timeout)
        return self.config

    def get_parameter_descriptions(self, timeout: float | None = None) -> list[dict[str, Any]] | None:
        self._wait(self._description_received, timeout)
        return self.param_description

    def get_group_descriptions(self, timeout: float | None = None) -> dict[str, Any] | None:
        self._wait(self._description_received, timeout)
        return self.group_description

    def update_configuration(self, changes: dict[str, Any]) -> Config:
        """Send `changes` (values converted to each parameter's type); returns the configuration the server kept."""
        changes = dict(changes)
        params = {p["name"]: p for p in self.get_parameter_descriptions() or []}
        for name, value in list(changes.items()):
            if name == "groups":
                continue
            if name not in params:
                raise DynamicReconfigureParameterException(f"don't know parameter: {name}")
            changes[name] = converted(value, params[name])
        if "groups" in changes:
            changes["groups"] = self._with_group_states(changes["groups"])
        try:
            answer = self._set_service(encode_config(changes)).config
        except ServiceException:
            raise DynamicReconfigureCallbackException("service call failed") from None
        return decode_config(answer, self.get_group_descriptions())

    def _with_group_states(self, states: dict[str, bool]) -> dict[str, Any]:
        tree = self.get_group_descriptions() or {}

        def update(group: dict[str, Any]) -> None:
            for child in group["groups"].values():
                if child["name"] in states:
                    child["state"] = states[child["name"]]
                update(child)

        update(tree)
        return tree

    def close(self) -> None:
        self._descriptions_sub.unregister()
        self._updates_sub.unregister()

    @property
    def config_callback(self) -> Callable[[Config], Any] | None:
        return self._config_callback

    @config_callback.setter
    def config_callback(self, value: Callable[[Config], Any] | None) -> None:
        self._config_callback = value
        if value is not None:
            value(self.config)  # type: ignore[arg-type]

    @property
    def description_callback(self) -> Callable[[list[dict[str, Any]]], Any] | None:
        return self._description_callback

    @description_callback.setter
    def description_callback(self, value: Callable[[list[dict[str, Any]]], Any] | None) -> None:
        self._description_callback = value
        if value is not None:
            value(self.param_description)  # type: ignore[arg-type]

    def _updates_msg(self, msg: Any) -> None:
        self._wait(self._description_received, None)
        self.config = decode_config(msg, self.group_description)
        self._config_received.set()
        if self._config_callback is not None:
            self._config_callback(self.config)

    def _descriptions_msg(self, msg: Any) -> None:
        self.group_description = decode_description(msg)
        self.param_description = extract_params(self.group_description)
        self._description_received.set()
        if self._description_callback is not None:
            self._description_callback(self.param_description)
