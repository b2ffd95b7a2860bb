"""Fields and constants named like Python keywords get a trailing underscore, as genpy names
them: the package stays importable and the bytes and md5sums are Debian genpy's."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from io import BytesIO
from pathlib import Path

import pytest

import genpy
from genpy.dynamic import generate_dynamic

from . import debian

DEFINITION = "int32 IF=7\nint32 if=2\nint32 from\nstring class\nfloat64 self\nuint8[] lambda\nint32 plain\n"
FULL_TEXT = DEFINITION


def test_dynamic_class_renames_keyword_fields() -> None:
    cls = generate_dynamic("kw_pkg/Keywords", FULL_TEXT)["kw_pkg/Keywords"]
    assert cls.__slots__ == ("from_", "class_", "self_", "lambda_", "plain")
    msg = cls(from_=3, class_="c", self_=1.5, lambda_=b"\x01\x02", plain=9)
    buff = BytesIO()
    msg.serialize(buff)
    back = cls().deserialize(buff.getvalue())
    assert (back.from_, back.class_, back.self_, back.lambda_, back.plain) == (3, "c", 1.5, b"\x01\x02", 9)
    assert "from_: 3" in str(back)


@pytest.mark.skipif(not debian.has("genpy"), reason="Debian's genpy is not installed")
def test_bytes_slots_and_md5_equal_debian_genpy() -> None:
    script = textwrap.dedent(f"""
        import json, io, genpy.dynamic
        cls = genpy.dynamic.generate_dynamic("kw_pkg/Keywords", {FULL_TEXT!r})["kw_pkg/Keywords"]
        m = cls(from_=-4, class_="k", self_=2.25, lambda_=b"ab", plain=1)
        b = io.BytesIO(); m.serialize(b)
        print(json.dumps([list(cls.__slots__), cls._md5sum, b.getvalue().hex(), cls.IF, cls.if_]))
    """)
    result = subprocess.run([str(debian.SYSTEM_PYTHON), "-c", script], capture_output=True, text=True,
                            env=debian.debian_env(), timeout=60)
    assert result.returncode == 0, result.stderr
    slots, md5, data, constant, keyword_constant = json.loads(result.stdout)
    cls = generate_dynamic("kw_pkg/Keywords", FULL_TEXT)["kw_pkg/Keywords"]
    msg = cls(from_=-4, class_="k", self_=2.25, lambda_=b"ab", plain=1)
    buff = BytesIO()
    msg.serialize(buff)
    assert [list(cls.__slots__), cls._md5sum, buff.getvalue().hex(), cls.IF, cls.if_] == [
        slots, md5, data, constant, keyword_constant]


def test_a_package_with_a_keyword_field_imports(tmp_path: Path) -> None:
    package = tmp_path / "kw_pkg"
    (package / "msg").mkdir(parents=True)
    (package / "package.xml").write_text("<package format='2'><name>kw_pkg</name><version>0.0.1</version>"
                                         "<description>d</description><maintainer email='m@e.org'>m</maintainer>"
                                         "<license>BSD</license></package>")
    (package / "msg" / "Keywords.msg").write_text(DEFINITION)
    (package / "msg" / "Plain.msg").write_text("int32 x\nKeywords inner\n")
    code = ("from kw_pkg.msg import Keywords, Plain\n"
            "p = Plain(x=1)\np.inner.from_ = 5\n"
            "import io; b = io.BytesIO(); p.serialize(b)\n"
            "print(Plain().deserialize(b.getvalue()).inner.from_, Keywords.IF)\n")
    env = {**debian.debian_env(), "ROS_PACKAGE_PATH": str(tmp_path)}
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=60)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["5", "7"]


def test_base_message_serializes_nothing() -> None:
    buff = BytesIO()
    genpy.Message().serialize(buff)
    assert buff.getvalue() == b""
