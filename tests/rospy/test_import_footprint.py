"""What `import rospy` and a message class load: a node that only publishes must not pay for
the asyncio event loop (with ssl), the message parser (dataclasses, inspect) or hashlib
(OpenSSL): together they were a third of an idle talker's memory (bench/RESULTS.md)."""

from __future__ import annotations

import json
import subprocess
import sys

HEAVY = ("asyncio", "ssl", "hashlib", "inspect", "dataclasses", "kame.msg.parser", "kame.msg.md5")


def test_a_publishing_node_imports_none_of_the_heavy_modules() -> None:
    probe = (
        "import json, sys\n"
        "import rospy\n"
        "from std_msgs.msg import String\n"
        "import kame.node.topics\n"
        "kame.node.topics.serialize_frame(String(data='hi'))\n"
        f"print(json.dumps([m for m in {HEAVY!r} if m in sys.modules]))\n"
    )
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=60, check=True)
    assert json.loads(out.stdout.strip().splitlines()[-1]) == []


def test_fixed_size_still_reads_definitions_when_asked() -> None:
    from kame.msg.size import fixed_size

    assert fixed_size("geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n") == 24
    assert fixed_size("std_msgs/String", "string data\n") is None
