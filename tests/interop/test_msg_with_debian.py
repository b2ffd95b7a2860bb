"""kame's messages against Debian's real ROS 1: genmsg md5sums, genpy definitions, bytes and str().

Runs debian_genpy_peer.py under /usr/bin/python3 (Debian's genmsg and genpy) once per
session and compares what it says with kame's answers for the same types and values.
"""

from __future__ import annotations

import json
import subprocess
from pathlib import Path
from typing import Any

import pytest

from kame.msg import MsgCatalog
from kame.msg.catalog import SHARE_DIR, Package, find_packages

from ..msg.test_messages import message_class, serialize
from ..msg.values import filled, to_plain

SYSTEM_PYTHON = Path("/usr/bin/python3")
DEBIAN_SHARE = Path("/usr/share")
PEER = Path(__file__).with_name("debian_genpy_peer.py")


def debian_has_genpy() -> bool:
    if not SYSTEM_PYTHON.exists() or not (DEBIAN_SHARE / "std_msgs" / "msg").is_dir():
        return False
    probe = subprocess.run([str(SYSTEM_PYTHON), "-c", "import genmsg, genpy, std_msgs.msg"], capture_output=True)
    return probe.returncode == 0


pytestmark = pytest.mark.skipif(not debian_has_genpy(), reason="Debian's ROS 1 (genmsg, genpy) is not installed")

KAME = MsgCatalog(find_packages([SHARE_DIR]))
DEBIAN_PACKAGES = sorted(p for p in KAME.packages if any((DEBIAN_SHARE / p / k).is_dir() for k in ("msg", "srv")))
MSG_TYPES = [t for p in DEBIAN_PACKAGES for t in KAME.message_types(p)
             if (DEBIAN_SHARE / p / "msg" / (t.split("/")[1] + ".msg")).exists()]
SRV_TYPES = [t for p in DEBIAN_PACKAGES for t in KAME.service_types(p)
             if (DEBIAN_SHARE / p / "srv" / (t.split("/")[1] + ".srv")).exists()]


@pytest.fixture(scope="module")
def debian() -> dict[str, Any]:
    samples = [{"type": t, "value": to_plain(filled(message_class(t)))} for t in MSG_TYPES]
    samples += [{"type": t, "value": to_plain(message_class(t)())} for t in MSG_TYPES]
    request = {"md5_types": MSG_TYPES, "srv_types": SRV_TYPES, "samples": samples}
    result = subprocess.run([str(SYSTEM_PYTHON), str(PEER)], input=json.dumps(request), capture_output=True,
                            text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    answer: dict[str, Any] = json.loads(result.stdout)
    return answer


def test_every_shipped_type_debian_has_is_covered() -> None:
    # kame ships these packages' definitions; Debian has all of them but the tutorials.
    assert len(DEBIAN_PACKAGES) >= 14
    assert len(MSG_TYPES) >= 140
    assert len(SRV_TYPES) >= 14


def test_md5sums_equal_genmsg_on_the_debian_definitions(debian: dict[str, Any]) -> None:
    differing = {t: (KAME.md5sum(t), debian["md5"][t]) for t in MSG_TYPES if KAME.md5sum(t) != debian["md5"][t]}
    assert differing == {}
    differing = {t: (KAME.srv_md5sum(t), debian["srv_md5"][t]) for t in SRV_TYPES
                 if KAME.srv_md5sum(t) != debian["srv_md5"][t]}
    assert differing == {}


def test_definition_texts_equal_genpy_on_the_same_files(debian: dict[str, Any]) -> None:
    # Read Debian's commented files with kame's parser: the full message_definition must be
    # the one genpy generated, byte for byte.
    on_debian_files = MsgCatalog({p: Package(p, DEBIAN_SHARE / p) for p in DEBIAN_PACKAGES})
    compared = 0
    for type_name, info in debian["classes"].items():
        assert on_debian_files.full_text(type_name) == info["full_text"], type_name
        assert on_debian_files.md5sum(type_name) == info["md5"], type_name
        compared += 1
    assert compared >= 100


def test_bytes_and_str_equal_genpy_for_the_same_values(debian: dict[str, Any]) -> None:
    compared = 0
    sample_types = MSG_TYPES + MSG_TYPES
    values = [filled(message_class(t)) for t in MSG_TYPES] + [message_class(t)() for t in MSG_TYPES]
    for type_name, msg, theirs in zip(sample_types, values, debian["samples"], strict=True):
        assert theirs["type"] == type_name
        if theirs.get("missing"):
            continue
        assert serialize(msg).hex() == theirs["hex"], type_name
        assert str(msg) == theirs["str"], type_name
        compared += 1
    assert compared >= 200
