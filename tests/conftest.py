"""Hypothesis profiles for the property-based tests (tests/fuzz), and the transport the tests run on.

- `--shm on|off|always`: kame's shared-memory topics (kame.net.shm) as the default (`on`: large
  messages through shared memory), off (plain TCPROS everywhere) or for every message
  (`always`); it sets KAME_SHM for the tests and every process they start. The suite passes
  each way: `scripts/test.sh --shm off`, `scripts/test.sh --shm always`.

- `ci` (the default): few examples, derandomized (the same examples every run, so a failure
  is reproducible and the suite stays deterministic), no deadline (a loaded machine is slow,
  not wrong), no example database written.
- `nightly`: many random examples; run with `HYPOTHESIS_PROFILE=nightly` (DEVELOPERS.md).
"""

from __future__ import annotations

import gc
import os
import sys
from collections.abc import Iterator

import pytest
from hypothesis import HealthCheck, settings

settings.register_profile("ci", max_examples=25, derandomize=True, deadline=None, database=None,
                          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
settings.register_profile("nightly", max_examples=2000, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

_SHM_MODES = {"on": "1", "off": "0", "always": "always"}


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--shm", choices=sorted(_SHM_MODES), default=None,
                     help="kame's shared-memory transport for the run: on (the default), off or always "
                          "(sets KAME_SHM for the tests and the processes they start)")


def pytest_configure(config: pytest.Config) -> None:
    mode = config.getoption("--shm")
    if mode is not None:
        os.environ["KAME_SHM"] = _SHM_MODES[mode]


def pytest_report_header(config: pytest.Config) -> str:
    return f"kame shared memory: KAME_SHM={os.environ.get('KAME_SHM', '1 (default)')}"


@pytest.hookimpl(hookwrapper=True, tryfirst=True)
def pytest_runtest_teardown(item: pytest.Item) -> Iterator[None]:
    yield
    _delete_what_qt_tests_left()


def _delete_what_qt_tests_left() -> None:
    """Every window a test leaves is deleted now, on the main thread, and its garbage collected here.

    A closed window's `deleteLater` waits for an event loop (a plain processEvents does not run it:
    one test left 100 such widgets), and a top-level widget belongs to its Python wrapper, so the
    cyclic collector run by any later test's thread (a process' output reader) could destroy it
    there while the main thread processed Qt events. The suite once died of a segmentation fault
    inside pytest-qt's processEvents with only such threads running."""
    widgets = sys.modules.get("PySide6.QtWidgets")
    if widgets is None or widgets.QApplication.instance() is None:
        return
    from PySide6.QtCore import QCoreApplication, QEvent

    for window in widgets.QApplication.topLevelWidgets():
        window.close()
        window.deleteLater()
    QCoreApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)
    gc.collect()
