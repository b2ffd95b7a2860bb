"""genmsg (names, msgs, msg_loader, srvs, gentools, deps, command_line, template_tools) and
genpy.generator's serializer writers against Debian's: tests/msg/genmsg_driver.py asks both
interpreters the same questions and the answers must be equal."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from tests.libs import debian

DRIVER = Path(__file__).with_name("genmsg_driver.py")

REQUEST: dict[str, Any] = {
    "names": ["std_msgs/String", "String", "a/b/c", "", "1bad", "ok_name", "pkg//T", "pkg/", " pkg/ ", "x-y"],
    "types": ["int32", "int32[]", "int32[3]", "int32[3][4]", "int32[x]", "Header", "Header[]", "std_msgs/Header",
              "roslib/Header", "time", "duration[2]", "String", "geometry_msgs/Point[]", "", " int32", "a/b/c",
              "string", "char", "bool[", "1x"],
    "texts": [
        ["p/Fields", "# leading comment\nint32 x  # trailing\nfloat64[] ys\nuint8[4] tag\nHeader header\n"
                     "Point p\ngeometry_msgs/Pose[2] poses\ntime t\nduration d\nstring s\n"],
        ["p/Consts", "int32 A=1\nuint8 B = 255 # c\nstring S=hello # not a comment\nstring T = spaced  \n"
                     "float64 F=1.5\nbool Y=True\nbool N=0\nchar C=65\nbyte D=-3\nint32 x\n"],
        ["p/Headed", "Header header\nint32 x\n"],
        ["Local", "Other o\nHeader h\nint32 x\n"],
        ["p/Empty", ""],
        ["p/Bad1", "int32 x y\n"],
        ["p/Bad2", "int32\n"],
        ["p/Bad3", "uint8 B=256\n"],
        ["p/Bad4", "Foo[x] f\n"],
        ["p/Bad5", "int32 1x\n"],
        ["p/Bad6", "int32 a\nint32 a\n"],
        ["p/Bad7", "foo X=1\n"],
    ],
    "constants": [["int8", "-128"], ["int8", "128"], ["uint16", "65535"], ["uint16", "-1"], ["float32", "2.5"],
                  ["float64", "x"], ["string", "  a b # c "], ["bool", "False"], ["bool", "2"], ["char", "255"],
                  ["byte", "-129"], ["int64", "9223372036854775807"], ["time", "1"]],
    "srv_text": "# request\nint32 a # first\nstring S=x # y\n---\n# response\nint64 sum\n---\nbool extra\n",
    "package": {
        "name": "kame_genmsg_test",
        "msg": {"Reading": "Header header\nfloat64[] values\nuint8[4] tag\nbool[3] flags\nstring from\nint32 KIND=3\n",
                "Pair": "# a pair of readings\nReading a\nReading b\ntime stamp\nduration[2] spans\n"
                        "geometry_msgs/Pose pose\nstring[] labels\nReading[2] fixed\nReading[] many\n",
                "Simple": "int32 x\nfloat64 y\nbool ok\nuint8 b\nint16 s\n",
                "Quoted": "string S=\"\"\"triple\"\"\"\nint32 x\n"},
        "srv": {"Measure": "string what\nint32 count # how many\n---\nReading result\nbool ok\n"},
    },
    "generate": ["kame_genmsg_test/Simple", "kame_genmsg_test/Reading", "kame_genmsg_test/Pair",
                 "geometry_msgs/PoseStamped"],
    "fields": [["string", "name"], ["time", "stamp"], ["uint8[]", "data"], ["int32[4]", "fixed"],
               ["bool[2]", "flags"], ["Reading", "reading"], ["kame_genmsg_test/Reading[]", "readings"],
               ["geometry_msgs/Point[3]", "points"], ["string[]", "names"], ["no_pkg/Missing", "m"]],
    "templates": {"msg.em": "@(spec.short_name) @(md5sum)\n@(msg_definition)\n@(file_name_in.split('/')[-1])\n",
                  "srv.em": "@(spec.short_name) @(md5sum) @(spec.request.names)\n",
                  "module.em": "@(package) @(sorted(files))\n"},
}

pytestmark = pytest.mark.skipif(not debian.has("genmsg", "genpy", "em"), reason="Debian's genmsg, genpy, empy absent")


@pytest.fixture(scope="module")
def answers() -> tuple[dict[str, Any], dict[str, Any]]:
    import sys

    return debian.run(DRIVER, REQUEST, sys.executable), debian.run(DRIVER, REQUEST)


def test_names_and_type_rules_answer_as_debians(answers: tuple[dict[str, Any], dict[str, Any]]) -> None:
    ours, theirs = answers
    assert ours["names"] == theirs["names"]
    assert ours["names"]["a/b/c"][0] == ["error", "ValueError", "invalid name [a/b/c]"]
    assert ours["msgs"] == theirs["msgs"]
    assert ours["msgs"]["int32[3][4]"][2][0] == "error"


def test_loading_definitions_answers_as_debians(answers: tuple[dict[str, Any], dict[str, Any]]) -> None:
    ours, theirs = answers
    for key, theirs_value in theirs["loader"]["texts"].items():
        assert ours["loader"]["texts"][key] == theirs_value, key
    assert ours["loader"]["constants"] == theirs["loader"]["constants"]
    assert ours["loader"]["srv"] == theirs["loader"]["srv"]
    assert ours["loader"]["default_context"] == theirs["loader"]["default_context"]
    local = ours["loader"]["texts"]["Local Other o\nHeader h\nint32 x\n"][1]
    assert local["types"] == ["Other", "std_msgs/Header", "int32"]


def test_package_md5s_texts_and_dependencies_as_debians(answers: tuple[dict[str, Any], dict[str, Any]]) -> None:
    ours, theirs = answers
    for key in ("Reading", "Pair", "Simple", "Quoted", "Measure", "missing", "full_type_name", "includepath"):
        assert ours["package"][key] == theirs["package"][key], key
    assert ours["package"]["Pair"][2][:2] == ["kame_genmsg_test/Reading", "std_msgs/Header"]
    assert '\\"\\"\\"triple' in ours["package"]["Quoted"][7]


def test_genpy_serializer_writers_write_genpys_lines(answers: tuple[dict[str, Any], dict[str, Any]]) -> None:
    ours, theirs = answers
    mine, real = ours["package"]["generator"], theirs["package"]["generator"]
    for key in real:
        assert mine[key] == real[key], key
    simple = mine["kame_genmsg_test/Simple"]
    assert simple["('serialize', False)"][1] == "  _x = self"
    assert "list(map(bool, self.flags))" in "\n".join(mine["kame_genmsg_test/Reading"]["('deserialize', False)"])


def test_templates_expand_as_debians(answers: tuple[dict[str, Any], dict[str, Any]]) -> None:
    ours, theirs = answers
    assert ours["package"]["templates"] == theirs["package"]["templates"]
    assert "Pair.txt" in ours["package"]["templates"]["files"]
