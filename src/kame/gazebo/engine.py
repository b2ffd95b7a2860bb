"""MuJoCo, imported once for the simulator with its warnings quiet, and its renderer's GL context
made on the first camera.

MuJoCo picks its OpenGL back end from MUJOCO_GL: EGL (Mesa) renders offscreen without a display
on these machines, where OSMesa failed; a caller's own choice (glfw on a desktop, osmesa
elsewhere) is kept (BACKEND). The back end's module is imported only when a camera needs a
context (gl_context_class), not with MuJoCo itself: importing it chooses PyOpenGL's platform for
the whole process (EGL's sets PYOPENGL_PLATFORM=egl), and a process that merely loads the
simulator (a test worker, a tool) must still be able to draw Qt's OpenGL windows, which use the
desktop's platform. PYOPENGL_PLATFORM is left as the caller had it, so that the programs this
process starts (rviz, gzclient) choose their own.
MuJoCo's default warning handler prints each warning and appends it to MUJOCO_LOG.TXT in the
current folder (a user's, wherever gzserver was started). The simulator's warnings are counted
in MjData, where kame.gazebo.world reads them and says what it did about them, so the handler
here lets them go.
"""

from __future__ import annotations

import os
from typing import Any

BACKEND = os.environ.get("MUJOCO_GL") or "egl"
_BACKENDS = ("egl", "osmesa", "glfw")

_callers_choice = os.environ.get("MUJOCO_GL")
os.environ["MUJOCO_GL"] = "disable"  # no GL module at import: see gl_context_class
try:
    import mujoco
finally:
    if _callers_choice is None:
        del os.environ["MUJOCO_GL"]
    else:
        os.environ["MUJOCO_GL"] = _callers_choice


def gl_context_class() -> Any:
    """MuJoCo's GLContext class for BACKEND, its module imported now (ImportError, OSError or
    AttributeError when the back end's libraries are missing)."""
    if BACKEND not in _BACKENDS:
        raise ImportError(f"MUJOCO_GL={BACKEND} is not one of MuJoCo's back ends here ({', '.join(_BACKENDS)})")
    platform = os.environ.get("PYOPENGL_PLATFORM")
    try:
        if BACKEND == "egl":
            from mujoco.egl import GLContext
        elif BACKEND == "osmesa":
            from mujoco.osmesa import GLContext
        else:
            from mujoco.glfw import GLContext
    finally:
        if platform is None:
            os.environ.pop("PYOPENGL_PLATFORM", None)
    return GLContext


def _counted_in_the_data(message: str) -> None:
    del message  # see the module's docstring


mujoco.set_mju_user_warning(_counted_in_the_data)

__all__ = ["BACKEND", "gl_context_class", "mujoco"]
