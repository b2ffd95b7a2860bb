"""kame's ROSRemoteRunner driving a real ROS child: a node on a <machine> that is not this one
(another user) is run by Debian's `roslaunch -c`, started here as sshd would start it (the
command through `sh -c`, its stdin and streams on pipes, in place of kame.net.ssh's connection),
which registers with kame's ROSLaunchParentNode, is sent its node as launch XML, and reports
its death back. Prints what happened as JSON.

`python roslaunch_remote_driver.py ENV_LOADER NODE_PACKAGE_PATH`
"""

from __future__ import annotations

import getpass
import io
import json
import subprocess
import sys
import threading
import traceback
from collections.abc import Callable
from contextlib import redirect_stderr, redirect_stdout
from typing import IO, Any

import roslaunch.config
import roslaunch.launch
import roslaunch.pmon
import roslaunch.remote
import roslaunch.remoteprocess
import roslaunch.server

TIMEOUT = 30.0


class LocalCommand:
    """kame.net.ssh.RemoteCommand's interface, the command run on this machine."""

    def __init__(self, target: Any, command: str, on_stdout: Callable[[str], None],
                 on_stderr: Callable[[str], None], on_end: Callable[[], None]) -> None:
        self.target = target
        self.popen = subprocess.Popen(["/bin/sh", "-c", command], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                      stderr=subprocess.PIPE)
        self._pending = 2
        self._lock = threading.Lock()
        self._on_end = on_end
        self._threads = [threading.Thread(target=self._pump, args=(s, c), daemon=True)
                         for s, c in ((self.popen.stdout, on_stdout), (self.popen.stderr, on_stderr))]
        for t in self._threads:
            t.start()

    def _pump(self, stream: IO[bytes], callback: Callable[[str], None]) -> None:
        for raw in stream:
            callback(raw.decode("utf-8", "replace").rstrip("\n"))
        with self._lock:
            self._pending -= 1
            last = self._pending == 0
        if last:
            self._on_end()

    def close_stdin(self) -> None:
        assert self.popen.stdin is not None
        self.popen.stdin.close()

    def wait(self, timeout: float) -> int | None:
        try:
            return self.popen.wait(timeout)
        except subprocess.TimeoutExpired:
            return None

    def close(self) -> None:
        if self.popen.poll() is None:
            self.popen.kill()
            self.popen.wait()
        for t in self._threads:
            t.join()


class Deaths(roslaunch.pmon.ProcessListener):
    def __init__(self) -> None:
        self.heard: list[list[Any]] = []
        self.remote_died = threading.Event()

    def process_died(self, process_name: str, exit_code: int) -> None:
        self.heard.append([process_name.rsplit("-", 1)[0], exit_code])
        if process_name.startswith("far_node"):
            self.remote_died.set()


def main(env_loader: str) -> dict[str, Any]:
    roslaunch.remoteprocess.SSHChildROSLaunchProcess.transport = LocalCommand
    other_user = getpass.getuser() + "_elsewhere"  # a machine that is this host, reached as someone else
    xml = (f'<launch><machine name="far" address="127.0.0.1" user="{other_user}" env-loader="{env_loader}"/>'
           '<param name="answer" value="42"/>'
           '<node machine="far" pkg="rl_pkg" type="exiter" name="far_node" args="6"/></launch>')
    config = roslaunch.config.load_config_default([], None, roslaunch_strs=[xml])
    pm = roslaunch.pmon.start_process_monitor()
    server = roslaunch.server.ROSLaunchParentNode(config, pm)
    deaths = Deaths()
    server.add_process_listener(deaths)
    server.start()
    remote = roslaunch.remote.ROSRemoteRunner("run-r", config, pm, server, sigint_timeout=2.0, sigterm_timeout=1.0)
    runner = roslaunch.launch.ROSLaunchRunner("run-r", config, server_uri=server.uri, pmon=pm, remote_runner=remote,
                                              sigint_timeout=2.0, sigterm_timeout=1.0)
    result: dict[str, Any] = {}
    try:
        remote.start_children()
        child = remote.remote_processes[0]
        result["child"] = [child.name, child.uri is not None, child.args[1:4], child.is_alive()]
        succeeded, failed = runner.launch()
        result["launched"] = [[s.rsplit("-", 1)[0] for s in succeeded], failed]
        result["died"] = deaths.remote_died.wait(TIMEOUT)
        result["heard"] = [d for d in deaths.heard if d[0] == "far_node"]
        result["answer"] = config.master.get().getParam("/t", "/answer")[2]
    finally:
        runner.stop()
        server.shutdown("over")
    result["child after stop"] = [child.is_alive(), child.command is None]
    return result


if __name__ == "__main__":
    out = io.StringIO()
    try:
        with redirect_stdout(out), redirect_stderr(io.StringIO()):
            answer = main(sys.argv[1])
    except Exception:
        traceback.print_exc()
        print(out.getvalue(), file=sys.stderr)
        sys.exit(2)
    roslaunch.pmon.pmon_shutdown()
    print(json.dumps(answer))
