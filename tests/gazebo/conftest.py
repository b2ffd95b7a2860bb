"""The simulator core's tests need MuJoCo (kame[gazebo]); without it they skip, saying so. MuJoCo is
imported through kame.gazebo.engine, which picks its headless (EGL) renderer before MuJoCo loads."""

from __future__ import annotations

import pytest

pytest.importorskip("kame.gazebo.engine", reason="kame[gazebo] is not installed (pip install 'kame[gazebo]')")
