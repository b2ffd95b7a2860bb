"""Runs a driver script under Debian's /usr/bin/python3 (real ROS 1 modules) and reads its JSON."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path
from typing import Any

SYSTEM_PYTHON = Path("/usr/bin/python3")


def has(*modules: str) -> bool:
    """True when Debian's interpreter imports every one of `modules`."""
    if not SYSTEM_PYTHON.exists():
        return False
    probe = subprocess.run([str(SYSTEM_PYTHON), "-c", "import " + ", ".join(modules)], capture_output=True,
                           env=debian_env(), timeout=60)
    return probe.returncode == 0


def debian_env() -> dict[str, str]:
    # without kame's paths: the system interpreter must import Debian's modules, not kame's
    return {key: value for key, value in os.environ.items() if key not in ("PYTHONPATH", "VIRTUAL_ENV")}


def run(script: Path, request: Any, python: str | Path = SYSTEM_PYTHON) -> Any:
    """`script` under `python` (Debian's by default; kame's as sys.executable) fed `request` as JSON."""
    result = subprocess.run([str(python), str(script)], input=json.dumps(request), capture_output=True,
                            text=True, timeout=120, env=debian_env())
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)
