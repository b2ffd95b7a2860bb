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

import os

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
