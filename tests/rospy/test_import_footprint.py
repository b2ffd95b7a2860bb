"""What `import rospy` and a message class load: a node that only publishes must not pay for
the asyncio event loop (with ssl), the message parser (dataclasses, inspect) or hashlib
(OpenSSL): together they were a third of an idle talker's memory (bench/RESULTS.md). Nor,
once it runs and serves a subscriber, for PyYAML, the email package, the idna codec, base64,
datetime, urllib.parse (with ipaddress) or the shared-memory transport (with ctypes) that it does
not use: another 6 MB."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from pathlib import Path

from ..support import Proc, free_port, kame_command, ros_env, wait_for_master

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


RUNNING_HEAVY = (*HEAVY, "yaml", "email", "encodings.idna", "base64", "datetime", "ctypes", "kame.net.shm",
                 "urllib.parse", "ipaddress")

_TALKER = """
import json, sys, time
import rospy
from std_msgs.msg import String
rospy.init_node("footprint_talker")
pub = rospy.Publisher("/footprint", String, queue_size=10)
deadline = time.monotonic() + 30
while pub.get_num_connections() < 1 and time.monotonic() < deadline:
    time.sleep(0.01)
connected = pub.get_num_connections()
for _ in range(50):
    pub.publish(String(data="hi"))
    time.sleep(0.01)
print(json.dumps([connected, [m for m in %r if m in sys.modules]]), flush=True)
"""

_LISTENER = """
import rospy
from std_msgs.msg import String
rospy.init_node("footprint_listener")
print(rospy.wait_for_message("/footprint", String, timeout=30).data, flush=True)
"""


def test_a_talker_serving_a_subscriber_loads_none_of_them(tmp_path: Path) -> None:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = {**ros_env(tmp_path, uri), "KAME_SHM": "0"}  # the shared-memory transport is loaded when used
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), env)
    procs: list[Proc] = []
    try:
        wait_for_master(uri, proc=master)
        procs.append(Proc([sys.executable, "-c", textwrap.dedent(_TALKER % (RUNNING_HEAVY,))], env))
        procs.append(Proc([sys.executable, "-c", textwrap.dedent(_LISTENER)], env))
        for proc in procs:
            proc.popen.wait(60)
    finally:
        outputs = [proc.stop() for proc in procs]
        master.stop()
    (talker_out, talker_err), (listener_out, listener_err) = outputs
    assert listener_out.split() == ["hi"], listener_err
    assert json.loads(talker_out.strip().splitlines()[-1]) == [1, []], talker_err
