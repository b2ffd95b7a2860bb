"""rosversion end to end: the installed console script, beside Debian's real one (rospkg's)
where both see the same packages."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

BIN = Path(sys.executable).parent
REAL = "/usr/bin/rosversion"

Result = subprocess.CompletedProcess[str]


@pytest.fixture(scope="module")
def ws(tmp_path_factory: pytest.TempPathFactory) -> Path:
    src = tmp_path_factory.mktemp("rosversion")
    for name, version in (("verpkg", "<version>2.4.6</version>"), ("nover", "")):
        (src / name).mkdir()
        (src / name / "package.xml").write_text(f'<package format="2"><name>{name}</name>{version}</package>')
    return src


def env_for(ws: Path, **extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
    env["ROS_PACKAGE_PATH"] = str(ws)
    env.update(extra)
    return env


def run(ws: Path, *args: str, exe: str | None = None, **extra: str) -> Result:
    return subprocess.run([exe or str(BIN / "rosversion"), *args], env=env_for(ws, **extra), capture_output=True,
                          text=True, timeout=30)


def test_distro_and_versions(ws: Path) -> None:
    assert run(ws, "-d").stdout == "noetic\n"
    assert run(ws, "-d", ROS_DISTRO="melodic").stdout == "melodic\n"
    assert run(ws, "roscpp").stdout == "1.15.15\n"
    assert run(ws, "rospy").stdout == "1.15.15\n"
    assert run(ws, "verpkg").stdout == "2.4.6\n"
    assert run(ws, "-s", "verpkg").stdout == "2.4.6"
    assert run(ws, "nover").stdout == "<unversioned>\n"
    unknown = run(ws, "nopkg")
    assert (unknown.returncode, unknown.stdout) == (1, "Cannot locate [nopkg]\n")
    bare = run(ws)
    assert bare.returncode == 2
    assert bare.stderr.endswith("rosversion: error: one of the arguments package -d/--distro -a/--all is required\n")
    listed = run(ws, "-a").stdout.splitlines()
    assert "verpkg: 2.4.6" in listed and "turtlesim: 0.10.2" in listed


@pytest.mark.skipif(not os.path.exists(REAL), reason="Debian's rosversion is not installed")
def test_same_as_real_rosversion(ws: Path) -> None:
    for args in (("roscpp",), ("rospy",), ("std_msgs",), ("verpkg",), ("-s", "verpkg"), ("nover",), ("nopkg",), (),
                 ("-h",), ("-d", "x")):
        ours, theirs = run(ws, *args), run(ws, *args, exe=REAL)
        assert (ours.returncode, ours.stdout, ours.stderr) == (theirs.returncode, theirs.stdout, theirs.stderr), args
    # Debian's says "Debian" where Noetic's says the distribution; with ROS_DISTRO set both print it
    assert run(ws, "-d", ROS_DISTRO="noetic").stdout == run(ws, "-d", exe=REAL, ROS_DISTRO="noetic").stdout
