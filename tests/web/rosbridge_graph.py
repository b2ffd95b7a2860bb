"""A live graph for the rosbridge tests: kame's roscore, `roslaunch rosbridge_server
rosbridge_websocket.launch` on a free port and turtlesim_node, each stopped by its PID."""

from __future__ import annotations

import shutil
import xmlrpc.client
from collections.abc import Iterator
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass
from pathlib import Path

from tests.support import Proc, free_port, kame_command, ros_env, wait_for_master, wait_until

WEB = Path(__file__).resolve().parent
NODE_MODULES = WEB / "node_modules"


@dataclass
class Graph:
    env: dict[str, str]
    master_uri: str
    port: int  # the bridge's
    launch: Proc

    @property
    def url(self) -> str:
        return f"ws://127.0.0.1:{self.port}"


@contextmanager
def bridge_graph(home: Path, *launch_args: str, turtlesim: bool = True) -> Iterator[Graph]:
    with ExitStack() as stack:
        master_port, port = free_port(), free_port()
        uri = f"http://127.0.0.1:{master_port}/"
        env = ros_env(home, uri)
        core = Proc(kame_command("kame.cli.roscore", "-p", str(master_port)), env)
        stack.callback(core.stop)
        wait_for_master(uri, proc=core)
        if turtlesim:
            turtle = Proc(kame_command("kame.cli.rosrun", "turtlesim", "turtlesim_node"), env)
            stack.callback(turtle.stop)
        launch = Proc(kame_command("kame.cli.roslaunch", "rosbridge_server", "rosbridge_websocket.launch",
                                   f"port:={port}", *launch_args), env)
        stack.callback(launch.stop)
        launch.wait_line("Rosbridge WebSocket server started", 60)
        master = xmlrpc.client.ServerProxy(uri)
        assert wait_until(lambda: master.lookupService("/test", "/rosapi/get_time")[0] == 1, 30), "no rosapi"
        if turtlesim:
            turtle.wait_line("Spawning turtle", 30)
        yield Graph(env, uri, port, launch)


def have_node_roslib() -> bool:
    return shutil.which("node") is not None and (NODE_MODULES / "roslib" / "package.json").is_file()
