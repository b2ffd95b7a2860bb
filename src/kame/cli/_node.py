"""What the node-running tools (rosbag record/play, rosout) share: their node, named from the
command line's special arguments as rospy names a node, and a stop event set by Ctrl-C,
SIGTERM or a master's shutdown request."""

from __future__ import annotations

import os
import signal
import threading
from collections.abc import Mapping
from typing import Any

from kame import environ
from kame.node.config import node_config
from kame.node.master_proxy import MasterError
from kame.node.node import Node


class ToolNode:
    """`__name`, `__ns`, `__master`, `__ip`/`__hostname` and remappings applied; the node is
    created, not yet registered with anything."""

    def __init__(self, special: Mapping[str, str], default_name: str,
                 remappings: Mapping[str, str] | None = None) -> None:
        config = node_config(default_name, special, os.environ, remappings)
        self.namespace = environ.namespace(os.environ, special)
        self.caller_id = config.name
        self.stop = threading.Event()

        def on_signal(signum: int, frame: Any) -> None:
            self.stop.set()

        signal.signal(signal.SIGINT, on_signal)
        signal.signal(signal.SIGTERM, on_signal)
        self.node = Node(config)
        self.node.on_shutdown_request = lambda reason: self.stop.set()

    def wait_for_master(self) -> bool:
        """Until the master answers (True), or the tool is stopped first (False)."""
        while True:
            try:
                self.node.master.call("getPid", timeout=2.0)
                return True
            except (OSError, MasterError):
                if self.stop.wait(0.2):
                    return False
