"""A fixture for the tests that render a camera."""

from __future__ import annotations

import pytest


@pytest.fixture(scope="session")
def renders() -> None:
    """Skips a test that renders a camera where MuJoCo cannot get a GL context, saying why (CI
    installs EGL's libraries: scripts/install-gui-libs.sh --xvfb)."""
    from kame.gazebo import GazeboError, World

    world = World.from_sdf('<sdf version="1.6"><model name="m"><static>true</static><link name="l">'
                           '<sensor name="c" type="camera"><camera><image><width>8</width><height>8</height>'
                           "</image></camera></sensor></link></model></sdf>")
    try:
        world.camera_frame(world.sensors()[0])
    except GazeboError as exc:
        pytest.skip(str(exc))
    finally:
        world.close()
