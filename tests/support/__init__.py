"""Shared test helpers: free loopback ports, processes stopped by PID, Debian's real ROS 1 tools.

Every process a test starts goes through `Proc`, which stops exactly that PID (SIGINT, then
SIGKILL) and never anything found by name.
"""

from __future__ import annotations

import os
import shutil
import signal
import socket
import subprocess
import sys
import time
import xmlrpc.client
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path

SYSTEM_PYTHON = "/usr/bin/python3"
REPO = Path(__file__).resolve().parents[2]


def free_port() -> int:
    """A TCP port on 127.0.0.1 that was free a moment ago."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def have_debian_ros() -> bool:
    """True when Debian's rosmaster, rospy and the ros* command-line tools can run."""
    if not (os.path.exists("/usr/bin/rosmaster") and os.path.exists(SYSTEM_PYTHON)):
        return False
    probe = subprocess.run([SYSTEM_PYTHON, "-c", "import rospy, rosmaster, rostopic"], capture_output=True)
    return probe.returncode == 0


def ros_env(home: Path, master_uri: str | None = None) -> dict[str, str]:
    """The environment for a ROS process: its own ROS_HOME/ROS_LOG_DIR, loopback addresses, no
    display (a simulator's window opens only in the tests that give it one)."""
    env = {k: v for k, v in os.environ.items()
           if not k.startswith("ROS_") and k not in ("PYTHONPATH", "DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
    home.mkdir(parents=True, exist_ok=True)
    env.update(ROS_HOME=str(home), ROS_LOG_DIR=str(home / "log"), ROS_HOSTNAME="127.0.0.1",
               PYTHONUNBUFFERED="1")
    if master_uri:
        env["ROS_MASTER_URI"] = master_uri
    return env


class Proc:
    """A started process, stopped by its PID; its output is collected line by line as it comes."""

    def __init__(self, args: Sequence[str], env: dict[str, str], cwd: Path | None = None,
                 stdin: int | None = None) -> None:
        """`stdin=subprocess.PIPE` keeps a program that reads its input (teleop) waiting for keys."""
        import threading

        self.args = list(args)
        self.popen = subprocess.Popen(self.args, env=env, cwd=cwd, stdin=stdin, stdout=subprocess.PIPE,
                                      stderr=subprocess.PIPE, text=True)
        self.out: list[str] = []
        self.err: list[str] = []
        self._readers = [threading.Thread(target=self._read, args=(stream, sink), daemon=True)
                         for stream, sink in ((self.popen.stdout, self.out), (self.popen.stderr, self.err))]
        for t in self._readers:
            t.start()

    @staticmethod
    def _read(stream: object, sink: list[str]) -> None:
        for line in stream:  # type: ignore[attr-defined]
            sink.append(line)

    @property
    def pid(self) -> int:
        return self.popen.pid

    def wait_line(self, text: str, timeout: float = 15.0) -> str:
        """The first stdout line containing `text`, waiting for it to appear."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            for line in list(self.out):
                if text in line:
                    return line
            if self.popen.poll() is not None and not any(t.is_alive() for t in self._readers):
                break
            time.sleep(0.02)
        raise AssertionError(f"{text!r} not printed by {self.args}:\n{''.join(self.out)}\n{''.join(self.err)}")

    def finish(self, timeout: float = 30.0) -> tuple[str, str]:
        """Waits for a program that ends by itself, which must exit 0; returns (stdout, stderr).
        One still running after `timeout` is stopped (SIGINT: a Python program's traceback then
        says where it waited) and fails with what it said, as does a nonzero exit."""
        late = ""
        try:
            self.popen.wait(timeout)
        except subprocess.TimeoutExpired:
            late = f"still running after {timeout:g} s, so stopped; "
        out, err = self.stop()
        assert not late and self.popen.returncode == 0, f"{late}exit {self.popen.returncode}\n{out}\n{err}"
        return out, err

    def stop(self, timeout: float = 5.0) -> tuple[str, str]:
        """SIGINT, then SIGKILL after `timeout`; returns (stdout, stderr)."""
        if self.popen.poll() is None:
            os.kill(self.pid, signal.SIGINT)
            try:
                self.popen.wait(timeout)
            except subprocess.TimeoutExpired:
                os.kill(self.pid, signal.SIGKILL)
                self.popen.wait(timeout)
        for t in self._readers:
            t.join(5)
        if self.popen.stdin is not None:
            self.popen.stdin.close()
        return "".join(self.out), "".join(self.err)


@contextmanager
def running(args: Sequence[str], env: dict[str, str], cwd: Path | None = None) -> Iterator[Proc]:
    proc = Proc(args, env, cwd)
    try:
        yield proc
    finally:
        proc.stop()


def kame_command(module: str, *args: str) -> list[str]:
    """Run a kame CLI module with this interpreter (works without installed entry points)."""
    return [sys.executable, "-m", module, *args]


def wait_until(condition: Callable[[], object], timeout: float = 10.0) -> bool:
    """Whether `condition()` came true within `timeout` seconds (polled every 10 ms): for state a
    test can only look at, such as another thread's counters or a node's links."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(0.01)
    return False


def wait_for_master(uri: str, timeout: float = 10.0, proc: Proc | None = None) -> None:
    deadline = time.monotonic() + timeout
    while True:
        try:
            code, _, _ = xmlrpc.client.ServerProxy(uri).getPid("/test")
            if code == 1:
                return
        except OSError:
            pass
        if proc is not None and proc.popen.poll() is not None:
            out, err = proc.stop()
            raise RuntimeError(f"{proc.args} exited with {proc.popen.returncode}:\n{out}\n{err}")
        if time.monotonic() > deadline:
            raise TimeoutError(f"no master at {uri}")
        time.sleep(0.05)


def ros_tool(name: str, *args: str, env: dict[str, str], timeout: float = 30.0,
             check: bool = True) -> subprocess.CompletedProcess[str]:
    """Run one of Debian's ROS 1 tools (rostopic, rosparam, ...) with the system interpreter."""
    path = shutil.which(name, path="/usr/bin") or name
    result = subprocess.run([SYSTEM_PYTHON, path, *args], env=env, capture_output=True, text=True,
                            timeout=timeout)
    if check and result.returncode != 0:
        raise AssertionError(f"{name} {' '.join(args)} failed ({result.returncode}):\n{result.stdout}\n{result.stderr}")
    return result


class LoopThread:
    """An asyncio event loop in a background thread, for serving from synchronous tests."""

    def __init__(self) -> None:
        import asyncio
        import threading

        self.loop = asyncio.new_event_loop()
        self.thread = threading.Thread(target=self.loop.run_forever, daemon=True)
        self.thread.start()

    def run(self, coro, timeout: float = 10.0):  # type: ignore[no-untyped-def]
        import asyncio

        return asyncio.run_coroutine_threadsafe(coro, self.loop).result(timeout)

    def close(self) -> None:
        self.loop.call_soon_threadsafe(self.loop.stop)
        self.thread.join(5)
        self.loop.close()


class FakeNode:
    """A node's XML-RPC server that records the master's calls (publisherUpdate, paramUpdate,
    shutdown) and answers [1, '', 0]; `delay` makes it slow."""

    def __init__(self, delay: float = 0.0) -> None:
        import threading
        from xmlrpc.server import SimpleXMLRPCServer

        self.calls: list[tuple[str, tuple[object, ...]]] = []
        self.event = threading.Event()
        self.delay = delay
        self.server = SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False, allow_none=False)
        self.server.register_instance(self)
        self.uri = f"http://127.0.0.1:{self.server.server_address[1]}/"
        self.thread = threading.Thread(target=self.server.serve_forever, kwargs={"poll_interval": 0.05},
                                       daemon=True)
        self.thread.start()

    def _dispatch(self, method: str, params: tuple[object, ...]) -> object:
        time.sleep(self.delay)
        self.calls.append((method, params))
        self.event.set()
        return [1, "", 0]

    def wait_calls(self, n: int, timeout: float = 5.0) -> list[tuple[str, tuple[object, ...]]]:
        deadline = time.monotonic() + timeout
        while len(self.calls) < n and time.monotonic() < deadline:
            time.sleep(0.01)
        return list(self.calls)

    def close(self) -> None:
        self.server.shutdown()
        self.server.server_close()


class SilentPeer:
    """A TCP listener that accepts connections and never answers: a node that hangs."""

    def __init__(self) -> None:
        import threading

        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(64)
        self.uri = f"http://127.0.0.1:{self.sock.getsockname()[1]}/"
        self.accepted: list[socket.socket] = []
        self.thread = threading.Thread(target=self._accept, daemon=True)
        self.thread.start()

    def _accept(self) -> None:
        while True:
            try:
                conn, _ = self.sock.accept()
            except OSError:
                return
            self.accepted.append(conn)

    def close(self) -> None:
        try:
            self.sock.shutdown(socket.SHUT_RDWR)  # wakes the blocked accept()
        except OSError:
            pass
        self.sock.close()
        for c in self.accepted:
            c.close()


def sending_to(master_uri: str, node: str, topic: str) -> set[str]:
    """The subscribers `node` is connected to and sending `topic` to, from its getBusInfo (empty
    while the node is not registered): publishing an unlatched message before a subscriber is
    in this set publishes it to nobody."""
    code, _, uri = xmlrpc.client.ServerProxy(master_uri).lookupNode("/test", node)
    if code != 1:
        return set()
    links = xmlrpc.client.ServerProxy(uri).getBusInfo("/test")[2]
    return {str(link[1]) for link in links if link[2] == "o" and link[4] == topic}
