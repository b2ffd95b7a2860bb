"""rqt_plot, rqt_console and rqt_logger_level started as a lesson starts them (the installed
commands, Qt offscreen) against a live turtlesim: each comes up (what it asks kame's master, seen
through a recording proxy in front of it), keeps running while the turtle hits the wall, and
ends on SIGINT or SIGTERM, leaving the master as it found it."""

from __future__ import annotations

import signal
import threading
import xmlrpc.client
from collections.abc import Iterator
from typing import Any
from xmlrpc.server import SimpleXMLRPCRequestHandler, SimpleXMLRPCServer

import pytest

from tests.support import Proc, sending_to
from tests.turtlesim.sim import BIN, Sim, turtlesim_with_rosout, wait_until

pytest.importorskip("PySide6")
pytest.importorskip("pyqtgraph")

WALL = "Oh no! I hit the wall!"


class RecordingMaster:
    """A master URI whose calls go to kame's master, each one noted (method, caller id, args)."""

    def __init__(self, uri: str) -> None:
        self.calls: list[tuple[str, str, tuple[Any, ...]]] = []
        self._lock = threading.Lock()
        self._local = threading.local()
        self._uri = uri

        class Quiet(SimpleXMLRPCRequestHandler):
            def log_message(self, format: str, *args: Any) -> None:
                pass

        self.server = SimpleXMLRPCServer(("127.0.0.1", 0), requestHandler=Quiet, allow_none=True, logRequests=False)
        self.server.register_instance(self)
        self.uri = f"http://127.0.0.1:{self.server.server_address[1]}/"
        self._thread = threading.Thread(target=self.server.serve_forever, daemon=True)
        self._thread.start()

    def _dispatch(self, method: str, params: tuple[Any, ...]) -> Any:
        with self._lock:
            self.calls.append((method, str(params[0]) if params else "", params[1:]))
        if not hasattr(self._local, "proxy"):  # one connection per serving thread
            self._local.proxy = xmlrpc.client.ServerProxy(self._uri, allow_none=True)
        return getattr(self._local.proxy, method)(*params)

    def by(self, prefix: str) -> list[tuple[str, str, tuple[Any, ...]]]:
        with self._lock:
            return [call for call in self.calls if call[1].startswith(prefix)]

    def close(self) -> None:
        self.server.shutdown()
        self.server.server_close()
        self._thread.join()


@pytest.fixture(scope="module")
def sim(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Sim]:
    with turtlesim_with_rosout(tmp_path_factory.mktemp("rqt_commands")) as live:
        yield live


@pytest.fixture
def recording(sim: Sim) -> Iterator[RecordingMaster]:
    proxy = RecordingMaster(sim.uri)
    yield proxy
    proxy.close()


def _tool(sim: Sim, proxy: RecordingMaster, *args: str) -> Proc:
    env = {k: v for k, v in sim.env.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    proc = Proc([str(BIN / args[0]), *args[1:]], dict(env, QT_QPA_PLATFORM="offscreen", ROS_MASTER_URI=proxy.uri),
                cwd=sim.home)
    sim.procs.append(proc)
    return proc


def _subscribed(proxy: RecordingMaster, prefix: str, topic: str) -> bool:
    return any(method == "registerSubscriber" and args[0] == topic for method, _, args in proxy.by(prefix))


def _alive(sim: Sim, proc: Proc) -> None:
    assert proc.popen.poll() is None, f"{proc.args} ended: {''.join(proc.err)}"


@pytest.mark.parametrize("how", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_plot_console_and_logger_level_come_up_keep_running_and_end(sim: Sim, recording: RecordingMaster,
                                                                    how: signal.Signals) -> None:
    plot = _tool(sim, recording, "rqt_plot", "/turtle1/pose/x:y")
    console = _tool(sim, recording, "rqt_console")
    levels = _tool(sim, recording, "rqt_logger_level")
    tools = {f"/rqt_plot_{plot.pid}": plot, f"/rqt_console_{console.pid}": console,
             f"/rqt_logger_level_{levels.pid}": levels}

    def up() -> bool:
        for proc in tools.values():
            _alive(sim, proc)
        return (_subscribed(recording, f"/rqt_plot_{plot.pid}", "/turtle1/pose")
                and _subscribed(recording, f"/rqt_console_{console.pid}", "/rosout_agg")
                and any(method == "getSystemState" for method, _, _ in recording.by(f"/rqt_logger_level_{levels.pid}")))

    wait_until(up, timeout=60, what="the three tools' first calls to the master")
    # the lesson: the turtle runs into the wall while they are open; its warning goes out on
    # /rosout_agg to rqt_console and to this echo
    echo = Proc([str(BIN / "rostopic"), "echo", "/rosout_agg/msg"], sim.env, cwd=sim.home)
    sim.procs.append(echo)
    console_name = f"/rqt_console_{console.pid}"

    def both_connected() -> bool:
        linked = sending_to(sim.uri, "/rosout", "/rosout_agg")
        return console_name in linked and any(name.startswith("/rostopic_") for name in linked)

    wait_until(both_connected, timeout=30, what="rqt_console's and the echo's links from /rosout")
    sim.run("rosservice", "call", "/reset")
    sim.run("rostopic", "pub", "-1", "/turtle1/cmd_vel", "geometry_msgs/Twist", "--", "[10,0,0]", "[0,0,0]")
    echo.wait_line(WALL, timeout=30)
    echo.stop()
    for proc in tools.values():
        _alive(sim, proc)
    for name, proc in tools.items():
        proc.popen.send_signal(how)
        assert proc.popen.wait(30) == 0, (name, proc.popen.returncode, "".join(proc.err))  # closed, not killed
        _, err = proc.stop()
        assert "Traceback" not in err, (name, err)
    # each node's subscriptions are gone from the master: no dead rqt node left in the graph
    state = xmlrpc.client.ServerProxy(sim.uri).getSystemState("/test")[2]
    left = {node for _, nodes in state[1] for node in nodes} | {node for _, nodes in state[0] for node in nodes}
    assert not left & set(tools), left & set(tools)
