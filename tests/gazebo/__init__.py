"""The simulator core's tests. Each module starts with `require_engine()`: without MuJoCo (the
kame[gazebo] extra), or with a MUJOCO_GL back end that cannot load, its tests skip, saying why.
A test that renders a camera runs `in_own_process`."""

from __future__ import annotations

import functools
import importlib
import multiprocessing
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from typing import Any

import pytest


def require_engine() -> None:
    try:
        import kame.gazebo.engine  # noqa: F401  (MuJoCo, loaded with the back end the engine chooses)
    except ImportError as exc:
        pytest.skip(f"{exc} (pip install 'kame[gazebo]')", allow_module_level=True)


def _run_unwrapped(module: str, name: str, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    getattr(importlib.import_module(module), name).__wrapped__(*args, **kwargs)


def in_own_process(test: Callable[..., None]) -> Callable[..., None]:
    """Runs the test in a fresh interpreter: a camera's GL context fixes PyOpenGL's platform (EGL)
    for the whole process, and the test worker then could not draw rviz's Qt views (GLX) in the
    tests that come after it."""

    @functools.wraps(test)
    def run(*args: Any, **kwargs: Any) -> None:
        with ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
            pool.submit(_run_unwrapped, test.__module__, test.__name__, args, kwargs).result()

    return run
