"""kame's message definitions as ROS ships them: the files byte for byte, and what they make
(`_full_text`, md5sums, a bag's connection records) equal to Debian's genpy and rosbag.

Debian's ROS 1 (/usr/share/<pkg>/msg|srv|action, /usr/bin/python3's genmsg, genpy, rosbag) is
the oracle; the tests skip when it is not installed.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path
from typing import Any

import pytest

from kame.msg.catalog import SHARE_DIR, MsgCatalog, find_packages
from tests.support import SYSTEM_PYTHON

DEBIAN_SHARE = Path("/usr/share")
KINDS = ("msg", "srv", "action")


def _debian(args: list[str], **kwargs: Any) -> subprocess.CompletedProcess[str]:
    """Debian's Python running `args`, without a PYTHONPATH that would put kame's packages first."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    return subprocess.run([SYSTEM_PYTHON, *args], capture_output=True, text=True, env=env, timeout=120, **kwargs)


def _debian_has(code: str) -> bool:
    if not Path(SYSTEM_PYTHON).exists() or not (DEBIAN_SHARE / "std_msgs" / "msg").is_dir():
        return False
    return _debian(["-c", code]).returncode == 0


debian_files = pytest.mark.skipif(not (DEBIAN_SHARE / "std_msgs" / "msg").is_dir(), reason="no Debian ROS files")
debian_genpy = pytest.mark.skipif(not _debian_has("import genmsg, genpy, std_msgs.msg"), reason="no Debian genpy")
debian_rosbag = pytest.mark.skipif(not _debian_has("import rosbag, geometry_msgs.msg"), reason="no Debian rosbag")


def _shipped_files_debian_has() -> list[Path]:
    """kame's definition files (relative to its share folder) that Debian also ships."""
    return sorted(path.relative_to(SHARE_DIR) for kind in KINDS for path in SHARE_DIR.glob(f"*/{kind}/*.{kind}")
                  if (DEBIAN_SHARE / path.relative_to(SHARE_DIR)).is_file())


@debian_files
def test_definition_files_debian_ships_are_byte_identical() -> None:
    files = _shipped_files_debian_has()
    assert len(files) >= 150
    differing = [str(rel) for rel in files if (SHARE_DIR / rel).read_bytes() != (DEBIAN_SHARE / rel).read_bytes()]
    assert differing == []


def _kame_classes() -> dict[str, type]:
    """Every generated class kame ships for the packages Debian has definitions of, by
    'pkg/kind/Name' (a service's Request and Response classes included)."""
    import importlib

    catalog = MsgCatalog(find_packages([SHARE_DIR]))
    classes: dict[str, type] = {}
    for package in catalog.packages:
        if not any((DEBIAN_SHARE / package / kind).is_dir() for kind in KINDS):
            continue
        for type_name in catalog.message_types(package):
            short = type_name.split("/")[1]
            classes[f"{package}/msg/{short}"] = getattr(importlib.import_module(f"{package}.msg"), short)
        for type_name in catalog.service_types(package):
            short = type_name.split("/")[1]
            module = importlib.import_module(f"{package}.srv")
            for suffix in ("Request", "Response"):
                classes[f"{package}/srv/{short}{suffix}"] = getattr(module, short + suffix)
    return classes


# For each key 'pkg/kind/Name': genpy's generated class's (_md5sum, _full_text) where Debian
# ships the Python package, else what genmsg computes from /usr/share's files, as genpy would.
DEBIAN_TEXTS = r"""
import importlib, json, os, sys
import genmsg.msg_loader as loader
from genmsg import gentools
SHARE = "/usr/share"
path = {}
for name in os.listdir(SHARE):
    folder = os.path.join(SHARE, name, "msg")
    if os.path.isdir(folder):
        path.setdefault(name, []).append(folder)
out = {}
for key in json.load(sys.stdin):
    package, kind, short = key.split("/")
    try:
        cls = getattr(importlib.import_module(package + "." + kind), short)
        out[key] = [cls._md5sum, cls._full_text, "genpy"]
        continue
    except (ImportError, AttributeError):
        pass
    context = loader.MsgContext.create_default()
    if kind == "msg":
        specs = [loader.load_msg_by_type(context, package + "/" + short, path)]
    else:
        name = short[:-len("Request")] if short.endswith("Request") else short[:-len("Response")]
        srv = loader.load_srv_from_file(context, os.path.join(SHARE, package, "srv", name + ".srv"),
                                        package + "/" + name)
        specs = [srv.request if short.endswith("Request") else srv.response]
    for spec in specs:
        loader.load_depends(context, spec, path)
        out[key] = [gentools.compute_md5(context, spec), gentools.compute_full_text(context, spec), "genmsg"]
print(json.dumps(out))
"""


@debian_genpy
def test_full_texts_and_md5sums_equal_debians() -> None:
    classes = _kame_classes()
    done = _debian(["-c", DEBIAN_TEXTS], input=json.dumps(sorted(classes)), check=True)
    theirs = json.loads(done.stdout)
    by_genpy = [key for key, (_, _, source) in theirs.items() if source == "genpy"]
    assert len(by_genpy) >= 160 and len(theirs) >= 180
    differing = {key: (cls._md5sum, cls._full_text) for key, cls in classes.items()  # type: ignore[attr-defined]
                 if [cls._md5sum, cls._full_text] != theirs[key][:2]}  # type: ignore[attr-defined]
    assert differing == {}


def test_int32_full_text_is_the_file_without_a_trailing_newline() -> None:
    from std_msgs.msg import Int32
    from std_srvs.srv import SetBoolRequest

    assert Int32._full_text == "int32 data"
    assert SetBoolRequest._full_text == "bool data # e.g. for hardware enabling / disabling\n"


READ_CONNECTIONS = r"""
import json, sys, rosbag
from geometry_msgs.msg import PoseStamped
from std_msgs.msg import Header
with rosbag.Bag(sys.argv[1]) as bag:
    conns = {c.topic: [c.datatype, c.md5sum, c.msg_def] for c in bag._get_connections()}
print(json.dumps({"conns": conns, "classes": {"/pose": PoseStamped._full_text, "/header": Header._full_text}}))
"""


@debian_rosbag
def test_bag_connection_records_carry_ros_definitions(tmp_path: Path) -> None:
    import rosbag
    from geometry_msgs.msg import PoseStamped
    from rospy import Time
    from std_msgs.msg import Header

    path = tmp_path / "defs.bag"
    with rosbag.Bag(path, "w") as bag:
        bag.write("/pose", PoseStamped(), Time(1, 0))
        bag.write("/header", Header(), Time(2, 0))
    done = _debian(["-c", READ_CONNECTIONS, str(path)], check=True)
    theirs = json.loads(done.stdout)
    assert theirs["conns"]["/pose"][2] == theirs["classes"]["/pose"] == PoseStamped._full_text
    assert theirs["conns"]["/header"][2] == theirs["classes"]["/header"]
    check = _debian(["/usr/bin/rosbag", "check", str(path)])
    assert "does not need any migrations" in check.stdout, check.stdout + check.stderr


KAME_PUBLISHER = r"""
import rospy
from geometry_msgs.msg import PoseStamped
rospy.init_node("kame_definitions_publisher")
pub = rospy.Publisher("/pose", PoseStamped, latch=True, queue_size=1)
pub.publish(PoseStamped())
print("published", flush=True)
rospy.spin()
"""

DEBIAN_SUBSCRIBER = r"""
import json, rospy
from geometry_msgs.msg import PoseStamped
rospy.init_node("debian_definitions_listener")
raw = rospy.wait_for_message("/pose", rospy.AnyMsg, timeout=30)
header = raw._connection_header
print(json.dumps({"definition": header["message_definition"], "md5sum": header["md5sum"],
                  "genpy": PoseStamped._full_text}))
"""


@debian_rosbag
def test_connection_header_carries_ros_definition(tmp_path: Path) -> None:
    """A kame publisher's connection header, as Debian's rospy receives it: the definition its
    own genpy class carries."""
    import sys

    from tests.support import free_port, ros_env, running, wait_for_master

    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = ros_env(tmp_path / "home", uri)
    with running([sys.executable, "-m", "kame.cli.rosmaster", "--core", "-p", str(port)], env) as master:
        wait_for_master(uri, proc=master)
        with running([sys.executable, "-c", KAME_PUBLISHER], env) as publisher:
            publisher.wait_line("published")
            done = subprocess.run([SYSTEM_PYTHON, "-c", DEBIAN_SUBSCRIBER], env=env, capture_output=True,
                                  text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    theirs = json.loads(done.stdout)
    from geometry_msgs.msg import PoseStamped

    assert theirs["definition"] == theirs["genpy"] == PoseStamped._full_text
    assert theirs["md5sum"] == PoseStamped._md5sum
