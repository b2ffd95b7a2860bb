"""The foxglove_bridge program: `rosrun foxglove_bridge foxglove_bridge _port:=8765`, or
`roslaunch foxglove_bridge foxglove_bridge.launch`. Its private parameters are Noetic's
foxglove_bridge's: port, address, topic_whitelist, param_whitelist, service_whitelist,
client_topic_whitelist, capabilities, max_update_ms and send_buffer_limit (bytes per client;
also the largest message a client may send). tls is refused: kame serves plain ws:// only.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from typing import Any

from kame.client import core, log
from kame.client.clock import get_rostime
from kame.client.process import get_param, init_node, spin
from kame.client.topics import Subscriber
from kame.foxglove_bridge.bridge import BridgeConfig, FoxgloveBridge
from rosgraph_msgs.msg import Clock


def _strings(value: Any, name: str) -> tuple[str, ...]:
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise ValueError(f"~{name} must be a list of strings")
    return tuple(value)


def read_config() -> BridgeConfig:
    defaults = BridgeConfig()

    def strings(name: str, default: tuple[str, ...]) -> tuple[str, ...]:
        return _strings(get_param(f"~{name}", list(default)), name)

    return BridgeConfig(
        address=str(get_param("~address", defaults.address)),
        port=int(get_param("~port", defaults.port)),
        topic_whitelist=strings("topic_whitelist", defaults.topic_whitelist),
        param_whitelist=strings("param_whitelist", defaults.param_whitelist),
        service_whitelist=strings("service_whitelist", defaults.service_whitelist),
        client_topic_whitelist=strings("client_topic_whitelist", defaults.client_topic_whitelist),
        capabilities=strings("capabilities", defaults.capabilities),
        max_update_ms=int(get_param("~max_update_ms", defaults.max_update_ms)),
        send_buffer_limit=int(get_param("~send_buffer_limit", defaults.send_buffer_limit)),
        use_sim_time=bool(get_param("/use_sim_time", False)))


def main(argv: Sequence[str] | None = None) -> int:
    init_node("foxglove_bridge", list(sys.argv if argv is None else argv))
    log.route_program_logs("kame.foxglove_bridge")
    if get_param("~tls", False):
        log.emit(log.ERROR, "foxglove_bridge: tls is not supported by kame's bridge (plain ws:// only)", ())
        return 1
    try:
        config = read_config()
    except (ValueError, TypeError) as exc:
        log.emit(log.ERROR, "foxglove_bridge: %s", (exc,))
        return 1
    node = core.get_node()
    assert node is not None
    try:
        bridge = FoxgloveBridge(node, config, lambda: int(get_rostime().to_nsec()))
    except OSError as exc:
        log.emit(log.ERROR, "Failed to start websocket server: %s", (exc,))
        return 1
    if config.use_sim_time:
        # the process's /clock subscription is kame.client's (its ROS time): the bridge shares it
        Subscriber("/clock", Clock, lambda msg: bridge.broadcast_time(int(msg.clock.to_nsec())))
    log.emit(log.INFO, "foxglove_bridge: serving ws://%s:%d", (config.address, bridge.hub.port))
    try:
        spin()
    finally:
        bridge.close()
    return 0
