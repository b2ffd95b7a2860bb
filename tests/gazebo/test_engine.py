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
    assert set(importers) == {"kame/gazebo/engine.py"}


def backend(environ: dict[str, str]) -> str:
    code = "import kame.gazebo.engine as e; print(e.BACKEND)"
    return subprocess.run([sys.executable, "-c", code], env=environ, capture_output=True, text=True, timeout=60,
                          check=True).stdout.strip()


def test_egl_unless_the_caller_chose() -> None:
    environ = {k: v for k, v in os.environ.items() if k != "MUJOCO_GL"}
    assert backend(environ) == "egl"
    assert backend({**environ, "MUJOCO_GL": "glfw"}) == "glfw"


def test_loading_the_simulator_leaves_pyopengl_alone_and_a_camera_leaves_the_environment() -> None:
    """A process that loads the simulator can still draw Qt's OpenGL windows (no PyOpenGL platform
    chosen); one that rendered a camera leaves PYOPENGL_PLATFORM unset for the programs it starts."""
    code = ("import os, sys\nfrom kame.gazebo import World\n"
            "print('OpenGL' in sys.modules)\n"
            "w = World.from_sdf('<sdf version=\"1.6\"><model name=\"m\"><static>true</static><link name=\"l\">"
            "<sensor name=\"c\" type=\"camera\"><camera><image><width>8</width><height>8</height></image></camera>"
            "</sensor></link></model></sdf>')\n"
            "w.camera_frame(w.sensors()[0])\nw.close()\n"
            "print('OpenGL' in sys.modules, os.environ.get('PYOPENGL_PLATFORM'), os.environ.get('MUJOCO_GL'))\n")
    environ = {k: v for k, v in os.environ.items() if k not in ("MUJOCO_GL", "PYOPENGL_PLATFORM")}
    out = subprocess.run([sys.executable, "-c", code], env=environ, capture_output=True, text=True, timeout=60)
    assert out.stdout.splitlines() == ["False", "True None None"], out.stdout + out.stderr
