"""MuJoCo is imported only through kame.gazebo.engine, which picks the headless EGL renderer unless
the caller chose another, before MuJoCo loads (MuJoCo reads MUJOCO_GL once, as it is imported)."""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from pathlib import Path

from tests.gazebo import require_engine

require_engine()

SRC = Path(__file__).resolve().parents[2] / "src"


def test_only_the_engine_module_imports_mujoco() -> None:
    importers = []
    for path in sorted(SRC.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                     else [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            if any(name == "mujoco" or name.startswith("mujoco.") for name in names):
                importers.append(str(path.relative_to(SRC)))
    assert importers == ["kame/gazebo/engine.py"]


def backend(environ: dict[str, str]) -> str:
    code = "import os, kame.gazebo.engine as e, mujoco; print(os.environ['MUJOCO_GL'])"
    return subprocess.run([sys.executable, "-c", code], env=environ, capture_output=True, text=True, timeout=60,
                          check=True).stdout.strip()


def test_egl_unless_the_caller_chose() -> None:
    environ = {k: v for k, v in os.environ.items() if k != "MUJOCO_GL"}
    assert backend(environ) == "egl"
    assert backend({**environ, "MUJOCO_GL": "glfw"}) == "glfw"
