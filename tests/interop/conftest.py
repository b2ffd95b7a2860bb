from __future__ import annotations

from pathlib import Path

import pytest

from ..support.roscpp import build_peers, roscpp_flags


@pytest.fixture(scope="session")
def cpp_peers() -> dict[str, Path]:
    """The compiled roscpp talker and listener (see tests/support/roscpp.py)."""
    flags = roscpp_flags()
    if flags is None:
        pytest.skip("g++ or roscpp's headers (pkg-config roscpp std_msgs) are not installed")
    return build_peers(flags)
