"""Test vectors recorded from real ROS 1 (see tests/data/README.md), kept in the repository."""

from __future__ import annotations

import functools
import json
from pathlib import Path
from typing import Any

VECTORS_PATH = Path(__file__).resolve().parent / "data" / "ros1_vectors.json"


@functools.cache
def vectors() -> dict[str, Any]:
    data: dict[str, Any] = json.loads(VECTORS_PATH.read_text())
    return data
