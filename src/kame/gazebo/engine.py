"""MuJoCo, imported once for the simulator with its renderer headless and its warnings quiet.

MuJoCo picks its OpenGL back end from MUJOCO_GL when it is first imported: EGL (Mesa) renders
offscreen without a display on these machines, where OSMesa failed. A caller's own choice
(glfw on a desktop, osmesa elsewhere) is kept.
MuJoCo's default warning handler prints each warning and appends it to MUJOCO_LOG.TXT in the
current folder (a user's, wherever gzserver was started). The simulator's warnings are counted
in MjData, where kame.gazebo.world reads them and says what it did about them, so the handler
here lets them go.
"""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

try:
    import mujoco  # after MUJOCO_GL: the back end is chosen at import
except ModuleNotFoundError:
    raise
except (ImportError, AttributeError, OSError) as exc:  # the chosen back end's libraries, not MuJoCo, are missing
    raise ImportError(f"MuJoCo cannot load its MUJOCO_GL={os.environ['MUJOCO_GL']} back end ({exc}); unset "
                      f"MUJOCO_GL for EGL, which renders headless") from exc


def _counted_in_the_data(message: str) -> None:
    del message  # see the module's docstring


mujoco.set_mju_user_warning(_counted_in_the_data)

__all__ = ["mujoco"]
