"""A real rospy node (Debian) drives kame's turtlesim and reads its pose."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from tests.support import SYSTEM_PYTHON, have_debian_ros
from tests.turtlesim.sim import turtlesim

DRIVER = Path(__file__).with_name("debian_driver.py")


@pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 is not installed")
def test_real_rospy_drives_kames_turtle(tmp_path: Path) -> None:
    with turtlesim(tmp_path) as (sim, _node):
        result = subprocess.run([SYSTEM_PYTHON, str(DRIVER)], env=sim.env, capture_output=True, text=True,
                                timeout=60)
        assert result.returncode == 0, result.stderr
        lines = dict(line.split(" ", 1) for line in result.stdout.splitlines())
        x0, y0 = map(float, lines["start"].split())
        x1, y1, theta, kind, span = lines["end"].split()
        assert kind == "turtlesim/Pose"
        assert (x0, y0) == pytest.approx((5.544445, 5.544445), abs=1e-5)
        # about 1.4-1.5 s of v=1, w=0.5 (five commands 0.1 s apart, then the 1 s timeout); a
        # driver held up while sending (span over 0.4 s) keeps the turtle going that much longer
        assert 1.2 < float(theta) / 0.5 < 1.7 + max(0.0, float(span) - 0.4)
        assert float(x1) > x0 + 1.0 and float(y1) > y0 + 0.2
