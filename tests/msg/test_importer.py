"""User packages on ROS_PACKAGE_PATH import with no build step."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

PACKAGE_XML = """<?xml version="1.0"?>
<package format="2">
  <name>{name}</name><version>0.1.0</version><description>test package</description>
  <maintainer email="t@example.org">t</maintainer><license>BSD</license>
</package>
"""


def make_package(root: Path, name: str, files: dict[str, str]) -> Path:
    pkg = root / name
    pkg.mkdir(parents=True)
    (pkg / "package.xml").write_text(PACKAGE_XML.format(name=name))
    for rel, text in files.items():
        path = pkg / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return pkg


def run(code: str, package_path: Path) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, ROS_PACKAGE_PATH=str(package_path))
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], env=env, capture_output=True,
                          text=True, timeout=60, cwd=str(package_path))


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    src = tmp_path / "src"
    make_package(src, "beginner_tutorials", {
        "msg/Num.msg": "int64 num\n",
        "msg/Stamped.msg": "# a stamped list\nHeader header\nNum[] nums\ngeometry_msgs/Point where\n",
        "srv/AddTwoInts.srv": "int64 a\nint64 b\n---\nint64 sum\n",
        "action/Count.action": "int32 to\n---\nint32 reached\n---\nint32 at\n",
    })
    make_package(src, "other_pkg", {"msg/UsesNum.msg": "beginner_tutorials/Num n\n"})
    return src


def test_import_before_rospy_with_no_build(workspace: Path) -> None:
    result = run("""
        from beginner_tutorials.srv import AddTwoInts, AddTwoIntsRequest, AddTwoIntsResponse
        from beginner_tutorials.msg import Num, Stamped, CountAction, CountGoal
        from other_pkg.msg import UsesNum
        import io, std_msgs.msg
        print(AddTwoInts._md5sum, AddTwoInts._request_class is AddTwoIntsRequest)
        s = Stamped(nums=[Num(5)])
        assert type(s.header) is std_msgs.msg.Header
        b = io.BytesIO(); s.serialize(b)
        assert Stamped().deserialize(b.getvalue()).nums[0].num == 5
        assert type(UsesNum().n) is Num
        print(Stamped._full_text.splitlines()[0], CountGoal().to, CountAction._type)
    """, workspace)
    assert result.returncode == 0, result.stderr
    first, second = result.stdout.splitlines()
    assert first == "6a2e34150c00229791cc89ff309fff21 True"
    assert second == "# a stamped list 0 beginner_tutorials/CountAction"


def test_edited_definitions_are_seen(workspace: Path) -> None:
    code = """
        import importlib
        import beginner_tutorials.msg as m
        print(m.Num.__slots__)
        open('beginner_tutorials/msg/Num.msg', 'w').write('int64 num\\nstring label\\n')
        m = importlib.reload(m)
        print(m.Num.__slots__)
    """
    result = run(code, workspace)
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == ["('num',)", "('num', 'label')"]
    again = run("from beginner_tutorials.msg import Num; print(Num.__slots__)", workspace)
    assert again.stdout.strip() == "('num', 'label')"


def test_a_missing_dependency_names_the_type_and_the_file(workspace: Path) -> None:
    (workspace / "beginner_tutorials" / "msg" / "Broken.msg").write_text("int8 a\nMissing m\n")
    result = run("from beginner_tutorials.msg import Broken", workspace)
    assert result.returncode == 1
    last = result.stderr.strip().splitlines()[-1]
    assert "Broken.msg: beginner_tutorials/Broken uses the type beginner_tutorials/Missing" in last


def test_unrelated_failed_imports_stay_import_errors(workspace: Path) -> None:
    result = run("""
        try:
            import no_such_module_anywhere
        except ImportError as e:
            print('ok', type(e).__name__)
        try:
            from beginner_tutorials.msg import NotThere
        except ImportError as e:
            print('ok', type(e).__name__)
    """, workspace)
    assert result.stdout.split() == ["ok", "ModuleNotFoundError", "ok", "ImportError"], result.stderr
