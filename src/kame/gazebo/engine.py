"""MuJoCo, imported once for the simulator with its renderer headless.

MuJoCo picks its OpenGL back end from MUJOCO_GL when it is first imported: EGL (Mesa) renders
offscreen without a display on these machines, where OSMesa failed. A caller's own choice
(glfw on a desktop, osmesa elsewhere) is kept.
"""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import mujoco  # after MUJOCO_GL: the back end is chosen at import

__all__ = ["mujoco"]
