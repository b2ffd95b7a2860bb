"""The shared ROS 1 spec folder beside the checkout, and its test vectors."""

from __future__ import annotations

import functools
import json
from pathlib import Path
from typing import Any

SPEC_DIR = Path(__file__).resolve().parents[2] / "shared" / "spec"


@functools.cache
def vectors() -> dict[str, Any]:
    path = SPEC_DIR / "vectors.json"
    if not path.exists():
        raise FileNotFoundError(f"the shared test vectors are missing: {path}")
    data: dict[str, Any] = json.loads(path.read_text())
    return data
