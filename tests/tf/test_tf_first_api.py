"""tf's first API (TransformerROS: lookups, transformPoint/Vector3/Quaternion/Pose, full
lookups, twists, errors) gives what Debian's tf gives, on the same script."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from ..support import SYSTEM_PYTHON

SCRIPT = Path(__file__).with_name("tf_first_api_script.py")


def have_debian_tf() -> bool:
    return subprocess.run([SYSTEM_PYTHON, "-c", "import tf, rospy"], capture_output=True).returncode == 0


def run(python: str) -> list[Any]:
    done = subprocess.run([python, str(SCRIPT)], capture_output=True, text=True, timeout=60, check=True)
    return json.loads(done.stdout.splitlines()[-1])  # type: ignore[no-any-return]


def close(a: Any, b: Any) -> bool:
    if isinstance(b, list):
        return isinstance(a, list) and len(a) == len(b) and all(close(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(b, float) and not isinstance(b, bool):
        return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-9)
    return bool(a == b)


@pytest.mark.skipif(not have_debian_tf(), reason="Debian's python3-tf is not installed")
def test_same_as_debians_tf() -> None:
    ours, theirs = run(sys.executable), run(SYSTEM_PYTHON)
    assert len(ours) == len(theirs)
    for index, (a, b) in enumerate(zip(ours, theirs, strict=True)):
        assert close(a, b), f"result {index}:\n kame: {a}\n tf:   {b}"
