"""The nodes of a launch that run on other machines: one roslaunch child per machine, over SSH.

Rules (roslaunch's remote and remoteprocess, with their console wording):
- Each machine that has nodes gets one child, named `<address>-<N>` (N counting from 0), started
  by `env ROS_MASTER_URI=<uri> <env-loader> roslaunch -c <name> --run_id <id> --sigint-timeout S
  --sigterm-timeout T` over SSH (kame.net.ssh: ssh-port, user, password or keys, known_hosts).
  The env-loader sets the remote environment up and runs its arguments (ROS's
  /opt/ros/<distro>/env.sh); without one, kame's own shell/env.sh at the path it has here.
- roslaunch's child registers back with the parent over XML-RPC and is sent its nodes as
  XML. kame's child is sent them as JSON on its stdin, and answers `kame-roslaunch-child ready`
  on its stdout: no port of the parent has to be reachable from the remote machine, and the
  SSH channel is the child's lifeline. The `<machine timeout>` (default 10 s) bounds the wait for
  that answer, failing as roslaunch's "failed to register".
- The child's stdout (its nodes' output="screen" lines and its process lines) is printed here as
  it comes; its stderr lines as `remote[<name>]: <line>` in red, as roslaunch does.
- Stopping closes the child's stdin: it stops its nodes (SIGINT, SIGTERM, SIGKILL as here) and
  exits; the connection is then closed. A connection that breaks stops the remote nodes too
  (the child sees the end of its stdin). A child that ends by itself is reported as a process.
"""

from __future__ import annotations

import asyncio
import logging
import shlex
from collections.abc import Sequence
from pathlib import Path

from kame.launch import plan
from kame.launch.model import Machine, Node
from kame.launch.supervisor import say, say_error
from kame.net.ssh import LOST, RemoteCommand, SshError, SshTarget

log = logging.getLogger("kame.launch.remote")

CHILD_READY = "kame-roslaunch-child ready"
DEFAULT_REGISTER_TIMEOUT = 10.0  # roslaunch's Machine timeout
STOP_GRACE = 5.0  # beyond the child's own SIGINT + SIGTERM timeouts, for its exit to reach us
ENV_LOADER = Path(__file__).resolve().parents[1] / "shell" / "env.sh"


def child_command(machine: Machine, name: str, run_id: str, master_uri: str, sigint_timeout: float,
                  sigterm_timeout: float) -> str:
    loader = machine.env_loader or str(ENV_LOADER)
    words = ["env", f"ROS_MASTER_URI={master_uri}", loader, "roslaunch", "-c", name, "--run_id", run_id,
             "--sigint-timeout", str(sigint_timeout), "--sigterm-timeout", str(sigterm_timeout)]
    return " ".join(shlex.quote(w) for w in words)


class RemoteChild:
    """The roslaunch child on one machine and its nodes."""

    def __init__(self, name: str, machine: Machine, nodes: Sequence[Node]) -> None:
        self.name = name
        self.machine = machine
        self.nodes = list(nodes)
        self.command: RemoteCommand | None = None
        self.ended = asyncio.Event()
        self.stopping = False
        self.gone = False
        self._ready = asyncio.Event()
        self._loop = asyncio.get_running_loop()

    @property
    def register_timeout(self) -> float:
        return self.machine.timeout or DEFAULT_REGISTER_TIMEOUT

    def alive(self) -> bool:
        return self.command is not None and not self.ended.is_set()

    # the reader threads' callbacks
    def _stdout(self, line: str) -> None:
        if line == CHILD_READY:
            self._loop.call_soon_threadsafe(self._ready.set)
        else:
            say(line)

    def _stderr(self, line: str) -> None:
        say_error(f"remote[{self.name}]: {line}")

    def _end(self) -> None:
        self._loop.call_soon_threadsafe(self.ended.set)

    async def start(self, run_id: str, master_uri: str, sigint_timeout: float, sigterm_timeout: float) -> str | None:
        """None once the child runs its nodes, else why it does not (printed already)."""
        m = self.machine
        say(f"remote[{self.name}] starting roslaunch")
        user = f", user[{m.user}]" if m.user is not None else ""
        say(f"remote[{self.name}]: creating ssh connection to {m.address}:{m.ssh_port}{user}")
        command = child_command(m, self.name, run_id, master_uri, sigint_timeout, sigterm_timeout)
        target = SshTarget(m.address, m.ssh_port, m.user, m.password)
        try:
            self.command = await asyncio.to_thread(RemoteCommand, target, command, self._stdout, self._stderr,
                                                   self._end)
        except SshError as exc:
            say_error(f"remote[{self.name}]: failed to launch on {m.name}:\n\n{exc}\n\n")
            return f"unable to start remote roslaunch child: {self.name}"
        say(f"launching remote roslaunch child with command: [{command}]")
        say(f"remote[{self.name}]: ssh connection created")
        await asyncio.to_thread(self.command.write, (plan.nodes_to_json(self.nodes) + "\n").encode())
        ready = asyncio.ensure_future(self._ready.wait())
        ended = asyncio.ensure_future(self.ended.wait())
        try:
            await asyncio.wait([ready, ended], timeout=self.register_timeout, return_when=asyncio.FIRST_COMPLETED)
        finally:
            ready.cancel()
            ended.cancel()
        if self._ready.is_set():
            return None
        if self.ended.is_set():
            return f"remote roslaunch failed to launch: {m.name}"
        return ("The following roslaunch remote processes failed to register: \n"
                f" * {m.name} (timeout {self.register_timeout:g}s)\n\n"
                "If this is a network latency issue, you may wish to consider setting \n"
                '  <machine timeout="NUMBER OF SECONDS" ... />\nin your launch')

    async def stop(self, sigint_timeout: float, sigterm_timeout: float) -> None:
        """The child told to stop its nodes (its stdin closed), waited for, and the connection closed."""
        self.stopping = True
        command = self.command
        if command is None:
            return
        await asyncio.to_thread(command.close_stdin)
        status = await asyncio.to_thread(command.wait, sigint_timeout + sigterm_timeout + STOP_GRACE)
        if status is None:
            say_error(f"remote[{self.name}]: unable to contact [{self.machine.address}] to shutdown remote "
                      "processes!")
        log.info("remote[%s]: closing ssh connection", self.name)
        await asyncio.to_thread(command.close)
        log.info("remote[%s]: ssh connection closed", self.name)

    async def exit_description(self) -> str:
        """What ended the child, once its streams have ended (its exit status follows them)."""
        command = self.command
        status = await asyncio.to_thread(command.wait, STOP_GRACE) if command is not None else None
        if status == 0:
            return "process has finished cleanly"
        if status is None or status == LOST:
            return f"process has died [the connection to {self.machine.address} was lost]."
        return f"process has died [exit code {status}, remote roslaunch on {self.machine.address}]."
