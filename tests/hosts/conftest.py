"""The hosts of a module of host tests: made once per module, with its master (tests/support/hosts.py)."""

from __future__ import annotations

import subprocess
from collections.abc import Iterator

import pytest

from ..support.hosts import Hosts


@pytest.fixture(scope="module")
def hosts(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Hosts]:
    try:
        h = Hosts(tmp_path_factory.mktemp("hosts"))
    except subprocess.CalledProcessError as exc:  # root without the right to make namespaces (a container)
        pytest.skip(f"cannot make network namespaces: {' '.join(exc.cmd)}: {exc.stderr.strip()}")
    try:
        yield h
    finally:
        h.close()


@pytest.fixture
def cleanup(hosts: Hosts) -> Iterator[Hosts]:
    """Stops what a test started on the hosts, keeping the module's master."""
    before = list(hosts.procs)
    try:
        yield hosts
    finally:
        for proc in [p for p in hosts.procs if p not in before]:
            hosts.stop(proc)
