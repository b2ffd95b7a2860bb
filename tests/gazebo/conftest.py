"""A fixture for the tests that render a camera."""

from __future__ import annotations

import multiprocessing
from concurrent.futures import ProcessPoolExecutor

import pytest


def render_problem() -> str | None:
    """Why MuJoCo cannot render a camera here, or None."""
    from kame.gazebo import GazeboError, World

    world = World.from_sdf('<sdf version="1.6"><model name="m"><static>true</static><link name="l">'
                           '<sensor name="c" type="camera"><camera><image><width>8</width><height>8</height>'
                           "</image></camera></sensor></link></model></sdf>")
    try:
        world.camera_frame(world.sensors()[0])
    except GazeboError as exc:
        return str(exc)
    finally:
        world.close()
    return None


@pytest.fixture(scope="session")
def renders() -> None:
    """Skips a test that renders a camera where MuJoCo cannot get a GL context, saying why (CI
    installs EGL's libraries: scripts/install-gui-libs.sh --xvfb). Tried in a child process, as the
    tests render (tests.gazebo.in_own_process)."""
    with ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
        problem = pool.submit(render_problem).result()
    if problem is not None:
        pytest.skip(problem)
