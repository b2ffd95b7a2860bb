"""The simulator core's tests need MuJoCo (kame[gazebo]); without it they skip, saying so."""

from __future__ import annotations

import pytest

pytest.importorskip("mujoco", reason="kame[gazebo] is not installed (pip install 'kame[gazebo]')")
