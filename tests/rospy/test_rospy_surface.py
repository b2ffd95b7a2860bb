"""Every public name of Debian's rospy modules (rospy, rospy/*, rospy/impl/*) is in kame's rospy
(tests/rospy/rospy_surface.py lists them under Debian's interpreter and looks them up under kame's)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from ..libs import debian

SURFACE = Path(__file__).parent / "rospy_surface.py"


def _has_ros_stream_handler() -> bool:
    from rosgraph import roslogging

    return hasattr(roslogging, "RosStreamHandler")


@pytest.mark.skipif(not debian.has("rospy"), reason="Debian's rospy is not installed")
def test_no_public_name_of_debians_rospy_is_missing() -> None:
    listing = subprocess.run([str(debian.SYSTEM_PYTHON), str(SURFACE), "list"], capture_output=True, text=True,
                             env=debian.debian_env(), timeout=120, check=True).stdout
    assert len(json.loads(listing)) > 20  # rospy, its modules and rospy.impl's
    missing = json.loads(subprocess.run([sys.executable, str(SURFACE), "missing"], input=listing,
                                        capture_output=True, text=True, timeout=120, check=True).stdout)
    # rospy.impl.init's RosStreamHandler is rosgraph.roslogging's class (rospy's adds nothing to
    # it), named here as soon as kame's rosgraph.roslogging has it
    allowed = {} if _has_ros_stream_handler() else {"rospy.impl.init": ["RosStreamHandler"]}
    assert missing == allowed
