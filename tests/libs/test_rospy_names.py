"""rospy.names: the same answers as Debian's rospy.names for a process that is not a node yet,
and scoped names and validators."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

import pytest

from . import debian

SCRIPT = textwrap.dedent("""
    import json, sys
    sys.argv = ["prog", "chatter:=/talk", "~p:=q", "_x:=1", "__ns:=/n"]
    import rospy.names as n
    out = [n.get_mappings(), n.scoped_name("/foo/node", "/foo/bar/name"), n.scoped_name("/node", "a//b/"),
           n.canonicalize_name("//a//b/"), n.remap_name("chatter", "/n/node"), n.remap_name("other", "/n/node"),
           n.valid_name("p")("rel", "/ns/node"), n.valid_name("p", False)("rel", "/ns/node"),
           n.global_name("p")("/g", "/ns/node")]
    for check in (lambda: n.valid_name("p")("", "/x"), lambda: n.valid_name("p")("a:b", "/x"),
                  lambda: n.global_name("p")("rel", "/x"), lambda: n.scoped_name("rel", "x")):
        try:
            check()
        except Exception as exc:
            out.append([type(exc).__name__, str(exc)])
    print(json.dumps(out))
""")


def run(python: str) -> list[object]:
    env = {**debian.debian_env(), "ROS_MASTER_URI": "http://127.0.0.1:1/"}
    result = subprocess.run([python, "-c", SCRIPT], capture_output=True, text=True, env=env, timeout=60)
    assert result.returncode == 0, result.stderr
    answer: list[object] = json.loads(result.stdout)
    return answer


@pytest.mark.skipif(not debian.has("rospy.names"), reason="Debian's rospy is not installed")
def test_same_answers_as_debians_rospy_names() -> None:
    theirs = run(str(debian.SYSTEM_PYTHON))
    assert theirs[0] == {"chatter": "/talk", "~p": "q", "__ns": "/n"}
    assert run(sys.executable) == theirs
