"""A short-lived child command, run to completion with a deadline: for probes that must not
take their parent down (a library that aborts the process when it starts, for one).

Rules: the child is ours; on the deadline it is killed by its own PID and reaped before we
return; its stdout and stderr come back as text, merged in the order it wrote them.
"""

from __future__ import annotations

import subprocess
from collections.abc import Mapping, Sequence
from dataclasses import dataclass


@dataclass(frozen=True)
class CommandResult:
    returncode: int | None  # None: killed on the deadline; negative: ended by that signal
    output: str  # stdout and stderr, interleaved


def run_command(args: Sequence[str], env: Mapping[str, str] | None = None, timeout: float = 20.0) -> CommandResult:
    """Run `args` to the end or to `timeout` seconds, whichever comes first."""
    with subprocess.Popen(list(args), env=dict(env) if env is not None else None, stdin=subprocess.DEVNULL,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT) as child:
        try:
            out, _ = child.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            child.kill()
            out, _ = child.communicate()
            return CommandResult(None, out.decode(errors="replace"))
        return CommandResult(child.returncode, out.decode(errors="replace"))
