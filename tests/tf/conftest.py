from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from .graph import Graph


@pytest.fixture
def graph(tmp_path: Path) -> Iterator[Graph]:
    """A kame master and the programs a test starts, all stopped by PID at the end."""
    g = Graph(tmp_path)
    try:
        yield g
    finally:
        g.stop()
