"""genpy's surface as Debian's (that no public name is missing is tests/test_module_surface.py's):
genpy.Message's base constructor, bool arrays read back as lists, the 'rosmsg' decoding handler,
generate_initpy and genpy_main (tests/msg/genpy_surface_driver.py run by both interpreters), and a
service whose request holds another package's message, generated without a NameError."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

import pytest

from tests.libs import debian

DRIVER = Path(__file__).with_name("genpy_surface_driver.py")
have_genpy = pytest.mark.skipif(not debian.has("genpy", "genmsg"), reason="Debian's genpy is not installed")


@pytest.fixture(scope="module")
def answers(tmp_path_factory: pytest.TempPathFactory) -> tuple[dict[str, Any], dict[str, Any]]:
    ours = debian.run(DRIVER, {"workdir": str(tmp_path_factory.mktemp("ours"))}, sys.executable)
    theirs = debian.run(DRIVER, {"workdir": str(tmp_path_factory.mktemp("theirs"))})
    return ours, theirs


@have_genpy
def test_message_base_constructor_is_genpys(answers: tuple[dict[str, Any], dict[str, Any]]) -> None:
    ours, theirs = answers
    assert ours["constructor"] == theirs["constructor"]
    assert ours["constructor"][1] == ["ok", [1, "x"]] and ours["constructor"][2] == ["ok", [2, "default"]]
    assert ours["constructor"][4][:2] == ["error", "TypeError"]


def test_message_subclass_calls_the_base_constructor() -> None:
    import genpy

    class Point2(genpy.Message):
        __slots__ = ("x", "y")
        _slot_types = ("float64", "float64")

        def __init__(self, *args: Any, **kwds: Any) -> None:
            super().__init__(*args, **kwds)
            self.y = 0.0 if self.y is None else self.y

    assert (Point2(x=1.5).x, Point2(x=1.5).y) == (1.5, 0.0)
    with pytest.raises(AttributeError, match="z is not an attribute of Point2"):
        Point2(z=1)


@have_genpy
def test_bool_arrays_read_back_as_lists(answers: tuple[dict[str, Any], dict[str, Any]]) -> None:
    ours, theirs = answers
    assert ours["bools"] == theirs["bools"]
    assert ours["bools"][1] == ["list", [True, False, True]]


def test_shipped_style_bool_arrays_are_lists_numpy_or_not() -> None:
    import io

    import numpy

    from kame.msg.loader import generate_dynamic

    cls = generate_dynamic("p/Flags", "bool[2] fixed\nbool[] var\n")["p/Flags"]
    buff = io.BytesIO()
    cls(fixed=[True, False], var=[True]).serialize(buff)
    for msg in (cls().deserialize(buff.getvalue()), cls().deserialize_numpy(buff.getvalue(), numpy)):
        assert (msg.fixed, msg.var) == ([True, False], [True])
        assert type(msg.fixed) is list and type(msg.var) is list


@have_genpy
def test_rosmsg_decoding_handler_and_isstring(answers: tuple[dict[str, Any], dict[str, Any]]) -> None:
    ours, theirs = answers
    assert ours["unicode"] == theirs["unicode"]
    assert ours["unicode"][0] == ["ok\ufffd", "\ufffd", "\ufffd"] and len(ours["unicode"][1]) == 2


@have_genpy
def test_generate_initpy_and_genpy_main_as_genpys(answers: tuple[dict[str, Any], dict[str, Any]]) -> None:
    ours, theirs = answers
    assert ours["initpy"] == theirs["initpy"]
    assert ours["initpy"]["init"] == "from ._A import *\nfrom ._B import *\n"
    assert ours["initpy"]["genmain"][0][0] == ["error", "SystemExit"]


def _package(root: Path, name: str, files: dict[str, str]) -> None:
    (root / name).mkdir()
    (root / name / "package.xml").write_text(
        f"<package format='2'><name>{name}</name><version>0.0.0</version><description>d</description>"
        "<maintainer email='a@b.c'>a</maintainer><license>BSD</license></package>\n")
    for rel, text in files.items():
        (root / name / rel).parent.mkdir(exist_ok=True)
        (root / name / rel).write_text(text)


def test_service_with_another_packages_message_in_its_request_generates(tmp_path: Path) -> None:
    # as ros_comm's test_rospy: TransitiveSrv's request holds TransitiveMsg1, which holds
    # TransitiveMsg2, which holds test_ros/Composite, which holds test_ros/CompositeA
    _package(tmp_path, "test_ros", {"msg/Composite.msg": "CompositeA a\nint32 b\n",
                                    "msg/CompositeA.msg": "float64 x\n"})
    _package(tmp_path, "test_rospy", {"msg/TransitiveMsg1.msg": "TransitiveMsg2 msg2\n",
                                      "msg/TransitiveMsg2.msg": "test_ros/Composite data\n",
                                      "srv/TransitiveSrv.srv": "test_rospy/TransitiveMsg1 msg\n---\nint32 a\n"})
    code = textwrap.dedent("""
        import io
        from test_rospy.msg import TransitiveMsg1
        from test_rospy.srv import TransitiveSrv, TransitiveSrvRequest
        request = TransitiveSrvRequest()
        request.msg.msg2.data.a.x = 2.5
        buff = io.BytesIO()
        request.serialize(buff)
        back = TransitiveSrvRequest().deserialize(buff.getvalue())
        print(back.msg.msg2.data.a.x, TransitiveMsg1().msg2.data.b,
              TransitiveSrv._request_class is TransitiveSrvRequest)
    """)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60,
                          env={**debian.debian_env(), "ROS_PACKAGE_PATH": str(tmp_path)})
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["2.5", "0", "True"]
