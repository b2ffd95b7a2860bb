"""A kame master and the processes of one action test, each stopped by its PID."""

from __future__ import annotations

import re
import sys
import time
from pathlib import Path

from ..support import REPO, SYSTEM_PYTHON, Proc, free_port, kame_command, ros_env, wait_for_master

PEERS = Path(__file__).with_name("peers")
PEER = PEERS / "move_base_peer.py"
TUTORIAL_SCRIPTS = REPO / "src" / "kame" / "share" / "actionlib_tutorials" / "scripts"
ALL_SCENARIOS = ["succeed", "cancel", "newer_goal", "cancel_all", "abort", "unknown_cancel", "simple"]
EXPECTED = """\
ready True
succeed ACTIVE WAITING_FOR_RESULT DONE SUCCEEDED 'done 3'
succeed-feedback 3 result MoveBaseResult
cancel ACTIVE WAITING_FOR_CANCEL_ACK PREEMPTING WAITING_FOR_RESULT DONE PREEMPTED 'preempted at N'
superseded ACTIVE PREEMPTING WAITING_FOR_RESULT DONE PREEMPTED 'preempted at N'
newer ACTIVE WAITING_FOR_RESULT DONE SUCCEEDED 'done 2'
cancel-all ACTIVE PREEMPTING WAITING_FOR_RESULT DONE PREEMPTED 'preempted at N'
abort ACTIVE WAITING_FOR_RESULT DONE ABORTED 'negative'
ghost-listed RECALLING
ghost-result RECALLED
simple-wait True SUCCEEDED 'done 2' True 2 done:SUCCEEDED
simple-and-wait SUCCEEDED
simple-timeout False ACTIVE
simple-canceled True PREEMPTED
simple-timed-out-goal PREEMPTED
FINISHED
"""


def normalized(out: str) -> str:
    """The client's observations without the step at which a preemption landed."""
    return "".join(re.sub(r"preempted at \d+", "preempted at N", line).rstrip() + "\n"
                   for line in out.splitlines())


class ActionGraph:
    def __init__(self, home: Path, params: dict[str, str] | None = None) -> None:
        port = free_port()
        self.uri = f"http://127.0.0.1:{port}/"
        self.env = ros_env(home, self.uri)
        self.procs: list[Proc] = []
        self.master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), self.env)
        wait_for_master(self.uri, proc=self.master)
        for name, value in (params or {}).items():
            self.run(kame_command("kame.cli.rosparam", "set", name, value))

    def start(self, args: list[str]) -> Proc:
        proc = Proc(args, self.env)
        self.procs.append(proc)
        return proc

    def run(self, args: list[str], timeout: float = 30.0) -> tuple[str, str]:
        proc = self.start(args)
        try:
            proc.popen.wait(timeout)
        except Exception:
            out, err = proc.stop()
            raise AssertionError(f"{args} did not finish in {timeout}s:\n{out}\n{err}") from None
        return proc.stop()

    def python(self, real: bool) -> str:
        return SYSTEM_PYTHON if real else sys.executable

    def server(self, real: bool = False) -> Proc:
        proc = self.start([self.python(real), str(PEER), "server"])
        proc.wait_line("SERVING")
        return proc

    def client(self, *scenarios: str, real: bool = False, timeout: float = 40.0) -> tuple[str, str]:
        start = time.monotonic()
        out, err = self.run([self.python(real), str(PEER), "client", *scenarios], timeout)
        assert "FINISHED" in out, f"client failed after {time.monotonic() - start:.1f}s:\n{out}\n{err}"
        return out, err

    def stop(self) -> None:
        for proc in reversed(self.procs):
            proc.stop()
        self.master.stop()
