"""Helpers for the shell tests: run a bash script with kame's setup.bash sourced."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from tests.support import ros_env

BIN = Path(sys.executable).parent
SETUP_BASH = subprocess.run([str(BIN / "kame-setup"), "--path"], capture_output=True, text=True,
                            check=True).stdout.strip()


def clean_env(home: Path, master_uri: str | None = None) -> dict[str, str]:
    """A user's environment before sourcing: no ROS_* variables, the venv not on PATH."""
    env = ros_env(home, master_uri)
    env["PATH"] = os.pathsep.join(p for p in env["PATH"].split(os.pathsep) if Path(p) != BIN)
    for name in ("CMAKE_PREFIX_PATH", "VIRTUAL_ENV", "ROS_LOCATIONS", "ROS_WORKSPACE"):
        env.pop(name, None)
    env["HOME"] = str(home)
    return env


def bash(script: str, env: dict[str, str], cwd: Path | None = None, setup: str = SETUP_BASH,
         timeout: float = 60.0) -> subprocess.CompletedProcess[str]:
    """Run `script` in a non-interactive bash after `source setup`."""
    text = f"source {setup}\n{script}"
    return subprocess.run(["bash", "-c", text], env=env, cwd=cwd, capture_output=True, text=True, timeout=timeout)


def complete_script(*words: str) -> str:
    """bash lines calling the completion function as bash does for `words` (last: the word being typed)."""
    quoted = " ".join("'" + w.replace("'", "'\\''") + "'" for w in words)
    return (f"COMP_WORDS=({quoted}); COMP_CWORD=$(( ${{#COMP_WORDS[@]}} - 1 )); COMP_LINE=\"${{COMP_WORDS[*]}}\"\n"
            f"fn=$(complete -p {words[0]} | sed -e 's/.*-F \\([^ ]*\\) .*/\\1/')\n"
            f"$fn {words[0]} \"${{COMP_WORDS[COMP_CWORD]}}\" \"${{COMP_WORDS[COMP_CWORD-1]}}\"\n"
            "printf '%s\\n' \"${COMPREPLY[@]}\"\n")


def complete(env: dict[str, str], *words: str, cwd: Path | None = None) -> list[str]:
    result = bash(complete_script(*words), env, cwd=cwd)
    assert result.returncode == 0, result.stderr
    return [line for line in result.stdout.splitlines() if line]
