"""Compile kame's bytecode before measuring, as `pip install` does (see compiled.sh)."""

from __future__ import annotations

import subprocess
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def compile_kame() -> None:
    python = REPO / ".venv" / "bin" / "python"
    if python.exists():
        subprocess.run([str(python), "-m", "compileall", "-q", str(REPO / "src")], stdout=subprocess.DEVNULL,
                       check=True)
