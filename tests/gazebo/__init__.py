"""The simulator core's tests. Each module starts with `require_engine()`: without MuJoCo (the
kame[gazebo] extra), or with a MUJOCO_GL back end that cannot load, its tests skip, saying why."""

from __future__ import annotations

import pytest


def require_engine() -> None:
    try:
        import kame.gazebo.engine  # noqa: F401  (MuJoCo, loaded with the back end the engine chooses)
    except ImportError as exc:
        pytest.skip(f"{exc} (pip install 'kame[gazebo]')", allow_module_level=True)
