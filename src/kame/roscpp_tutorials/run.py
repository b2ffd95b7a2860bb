"""Runs one roscpp tutorial program: the compiled one where this machine can build it, else the port.

The compiled program replaces this process (exec), so its PID, signals and exit status are the
program's own.
"""

from __future__ import annotations

import os
import sys

from kame.roscpp_tutorials.build import disabled, program


def main(name: str) -> int:
    binary = None if disabled(os.environ) else program(name, os.environ)
    if binary is not None:
        os.execv(binary, [str(binary), *sys.argv[1:]])
    from kame.roscpp_tutorials.ports import main as port

    return port(name, [name, *sys.argv[1:]])
