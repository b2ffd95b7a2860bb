"""rosgraph.roslogging: the same log files, `latest` link, line format and errors as Debian's
rosgraph (which reads ROS's python_logging.conf; kame's default is that configuration)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from . import debian

DRIVER = Path(__file__).with_name("roslogging_driver.py")


def run(python: str, log_dir: Path) -> dict[str, Any]:
    log_dir.mkdir()
    env = {k: v for k, v in debian.debian_env().items() if k != "ROS_PYTHON_LOG_CONFIG_FILE"}
    env.update(ROS_LOG_DIR=str(log_dir), ROS_HOME=str(log_dir.parent / "home"))
    result = subprocess.run([python, str(DRIVER), str(log_dir)], capture_output=True, text=True, env=env, timeout=60)
    assert result.returncode == 0, result.stderr
    answer: dict[str, Any] = json.loads(result.stdout)
    return answer


def test_configure_logging_writes_ros_logs(tmp_path: Path) -> None:
    ours = run(sys.executable, tmp_path / "logs")
    assert ours["first"] == "LOG/probe-PID.log" and ours["second"] == "LOG/run1/probe-x.log"
    assert ours["latest"] == "LOG/run1" and ours["lines"] == ["[probe.child][INFO] TIME: hello log"]
    assert ours["error"] == "Cannot save log files: file [LOG/blocked] is in the way"


@pytest.mark.skipif(not debian.has("rosgraph.roslogging"), reason="Debian's python3-rosgraph is not installed")
def test_the_same_as_debians_rosgraph(tmp_path: Path) -> None:
    assert run(sys.executable, tmp_path / "ours") == run(str(debian.SYSTEM_PYTHON), tmp_path / "theirs")
