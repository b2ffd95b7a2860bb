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


TF_MESSAGES = """
import io, json
from geometry_msgs.msg import TransformStamped
from tf.msg import tfMessage
from tf.srv import FrameGraph, FrameGraphRequest, FrameGraphResponse
t = TransformStamped()
t.header.frame_id, t.child_frame_id, t.header.seq = 'odom', 'base_link', 7
t.header.stamp.secs, t.header.stamp.nsecs = 12, 345
t.transform.translation.x, t.transform.rotation.z, t.transform.rotation.w = 1.5, 0.6, 0.8
out = io.BytesIO()
tfMessage(transforms=[t, t]).serialize(out)
graph = io.BytesIO()
FrameGraphResponse(dot_graph='digraph G {}').serialize(graph)
back = tfMessage()
back.deserialize(out.getvalue())
print(json.dumps([tfMessage._type, tfMessage._md5sum, tfMessage._full_text.splitlines()[0], FrameGraph._type,
                  FrameGraph._md5sum, FrameGraphRequest._md5sum, FrameGraphResponse._full_text.splitlines()[0],
                  out.getvalue().hex(),
                  graph.getvalue().hex(), back.transforms[1].child_frame_id]))
"""


@pytest.mark.skipif(not have_debian_tf(), reason="Debian's python3-tf is not installed")
def test_tf_msg_and_srv_are_debians() -> None:
    """tf/tfMessage (the old /tf type, still in old bags) and tf/FrameGraph: same type, md5sum,
    definition (kame's definitions carry no comments, as everywhere) and bytes as Debian's."""
    ours, theirs = ([json.loads(subprocess.run([python, "-c", TF_MESSAGES], capture_output=True, text=True,
                                               timeout=60, check=True).stdout)]
                    for python in (sys.executable, SYSTEM_PYTHON))
    assert ours == theirs
    assert ours[0][0] == "tf/tfMessage" and ours[0][-1] == "base_link"
