"""roslib.names, roslib.packages and roslib.message: against Debian's roslib where it can run."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest

import roslib.message
import roslib.names
import roslib.packages
import rospkg

from . import debian
from .calls_driver import run

DRIVER = Path(__file__).with_name("calls_driver.py")
RESOURCES = ["std_msgs/String", "String", "a/b/c", "/a", "a//b", "1a/b", "a_b/C_d", "", "pkg/", "é/x"]


@pytest.mark.skipif(not debian.has("roslib.names", "roslib.packages"), reason="Debian's roslib is not installed")
def test_names_and_finding_files_answer_as_debians_roslib(tmp_path: Path) -> None:
    package = tmp_path / "ws" / "pkg_a"
    (package / "scripts" / ".hidden").mkdir(parents=True)
    (package / "nodes").mkdir()
    (package / "package.xml").write_text("<package format='2'><name>pkg_a</name><version>1.0.0</version>"
                                         "<description>d</description><maintainer email='m@e.org'>m</maintainer>"
                                         "<license>BSD</license></package>")
    for rel, mode in [("scripts/talker", 0o755), ("nodes/talker", 0o644), ("scripts/.hidden/talker", 0o755),
                      ("scripts/data.yaml", 0o644)]:
        (package / rel).write_text("#!/usr/bin/env python3\n")
        (package / rel).chmod(mode)
    calls: list[list[Any]] = []
    for name in RESOURCES:
        for function in ("resource_name_base", "resource_name_package", "package_resource_name",
                         "is_legal_resource_name", "is_legal_resource_base_name"):
            calls.append(["roslib.names", function, [name]])
        calls.append(["roslib.names", "resource_name", [name, "T", "pkg"]])
        calls.append(["roslib.names", "resource_name", ["pkg", name, "pkg"]])
    for probe in (package / "scripts" / ".hidden", package, tmp_path):
        calls.append(["roslib.packages", "get_dir_pkg", [str(probe)]])
    theirs = debian.run(DRIVER, calls)
    assert run(calls) == theirs

    script = ("import json, sys, rospkg, roslib.packages as p\n"
              f"r = rospkg.RosPack([{str(tmp_path / 'ws')!r}])\n"
              "print(json.dumps([sorted(p.find_node('pkg_a', 'talker', rospack=r)),"
              " sorted(p.find_resource('pkg_a', 'talker', rospack=r)),"
              " sorted(p.find_resource('pkg_a', 'data.yaml', rospack=r))]))\n")
    debian_script = tmp_path / "find.py"
    debian_script.write_text(script)
    reference = debian.run(debian_script, None)
    rospack = rospkg.RosPack([str(tmp_path / "ws")])
    assert reference[0] == [str(package / "scripts" / "talker")]
    assert [sorted(roslib.packages.find_node("pkg_a", "talker", rospack=rospack)),
            sorted(roslib.packages.find_resource("pkg_a", "talker", rospack=rospack)),
            sorted(roslib.packages.find_resource("pkg_a", "data.yaml", rospack=rospack))] == reference


def test_package_folders(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    std_msgs = roslib.packages.get_pkg_dir("std_msgs")
    assert std_msgs is not None and os.path.isfile(os.path.join(std_msgs, "msg", "String.msg"))
    assert roslib.packages.get_pkg_dir("no_such_pkg", required=False) is None
    with pytest.raises(roslib.packages.InvalidROSPkgException, match="Cannot locate installation of package"):
        roslib.packages.get_pkg_dir("no_such_pkg")
    package = tmp_path / "mine"
    package.mkdir()
    (package / "package.xml").write_text("<package><name>mine</name></package>")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path))
    assert roslib.packages.get_pkg_dir("mine", ros_package_path=str(tmp_path)) == str(package)
    made = roslib.packages.get_pkg_subdir("mine", "data", env={"ROS_PACKAGE_PATH": str(tmp_path)})
    assert made == str(package / "data") and (package / "data").is_dir()
    assert roslib.packages.resource_file("mine", "data", "x.yaml") == str(package / "data" / "x.yaml")


def test_message_module_offers_the_base_class() -> None:
    from std_msgs.msg import String

    assert issubclass(String, roslib.message.Message)
    assert roslib.message.get_message_class("std_msgs/String") is String
    assert roslib.message.strify_message(String(data="hi")) == "data: \"hi\""
