"""kame.msg.describe: rosmsg's texts, type listings and lookup errors, on a small catalog."""

from __future__ import annotations

from pathlib import Path

import pytest

from kame.msg.catalog import SHARE_DIR, MsgCatalog
from kame.msg.describe import (
    Kind,
    all_types,
    describe_msg,
    describe_srv,
    find_by_short_name,
    load_msg,
    load_srv,
    packages_with,
    types_in_package,
)
from kame.msg.errors import MsgDefinitionError, MsgNotFoundError

PACKAGE_XML = "<package format='2'><name>{}</name><version>0.0.1</version></package>\n"


def package(root: Path, name: str, files: dict[str, str]) -> None:
    (root / name).mkdir()
    (root / name / "package.xml").write_text(PACKAGE_XML.format(name))
    for rel, text in files.items():
        (root / name / rel).parent.mkdir(exist_ok=True)
        (root / name / rel).write_text(text)


@pytest.fixture
def catalog(tmp_path: Path) -> MsgCatalog:
    package(tmp_path, "demo", {
        "msg/Pose.msg": "# comment\nint8 LEFT=-1\nstring S=a # b\nHeader header\nPoint[2] points\n",
        "msg/Point.msg": "float64 x\nfloat64 y\n",
        "msg/Broken.msg": "Missing m\n",
        "msg/Twist.msg": "int32 a\n",
        "srv/Ask.srv": "Point p\n---\nbool ok\n",
        "action/Go.action": "int32 goal\n---\n---\nfloat32 progress\n",
    })
    package(tmp_path, "nothing", {})
    return MsgCatalog.from_environment(str(tmp_path))


def test_describe_msg_expands_nested_types(catalog: MsgCatalog) -> None:
    assert describe_msg(catalog, load_msg(catalog, "demo/Pose")) == (
        "int8 LEFT=-1\n"
        "string S=a # b\n"
        "std_msgs/Header header\n  uint32 seq\n  time stamp\n  string frame_id\n"
        "demo/Point[2] points\n  float64 x\n  float64 y\n"
    )


def test_describe_srv(catalog: MsgCatalog) -> None:
    text = describe_srv(catalog, load_srv(catalog, "demo/Ask"))
    assert text == "demo/Point p\n  float64 x\n  float64 y\n---\nbool ok\n"


def test_describe_action_message(catalog: MsgCatalog) -> None:
    text = describe_msg(catalog, load_msg(catalog, "demo/GoActionFeedback"))
    assert text.startswith("std_msgs/Header header\n")
    assert text.endswith("demo/GoFeedback feedback\n  float32 progress\n")
    assert describe_msg(catalog, load_msg(catalog, "demo/GoResult")) == ""


def test_listing(catalog: MsgCatalog) -> None:
    assert types_in_package(catalog, "demo", Kind.SRV) == ["demo/Ask"]
    msgs = types_in_package(catalog, "demo", Kind.MSG)
    assert msgs[:4] == ["demo/Broken", "demo/GoAction", "demo/GoActionFeedback", "demo/GoActionGoal"]
    assert "demo/Point" in msgs and "demo/GoFeedback" in msgs
    assert "demo" in packages_with(catalog, Kind.MSG) and "nothing" not in packages_with(catalog, Kind.MSG)
    assert "geometry_msgs" in packages_with(catalog, Kind.MSG)
    assert "geometry_msgs" not in packages_with(catalog, Kind.SRV)
    everything = all_types(catalog, Kind.MSG)
    assert everything.index("demo/Twist") < everything.index("geometry_msgs/Twist")


def test_find_by_short_name(catalog: MsgCatalog) -> None:
    assert find_by_short_name(catalog, "Twist", Kind.MSG) == ["demo/Twist", "geometry_msgs/Twist"]
    assert find_by_short_name(catalog, "GoGoal", Kind.MSG) == ["demo/GoGoal"]
    assert find_by_short_name(catalog, "Ask", Kind.SRV) == ["demo/Ask"]
    assert find_by_short_name(catalog, "Ask", Kind.MSG) == []
    assert find_by_short_name(catalog, "Header[]", Kind.MSG) == []


def test_errors_worded_as_genmsg(catalog: MsgCatalog) -> None:
    with pytest.raises(MsgNotFoundError, match=r"^invalid name \[a/b/c\]$"):
        load_msg(catalog, "a/b/c")
    with pytest.raises(MsgNotFoundError) as unknown:
        load_srv(catalog, "nope/X")
    text = str(unknown.value)
    assert text.startswith("Cannot locate message [X]: unknown package [nope] on search path [{'demo': [")
    assert f"'std_srvs': ['{SHARE_DIR / 'std_srvs' / 'srv'}']" in text
    folder = catalog.packages["demo"].path / "msg"
    with pytest.raises(MsgNotFoundError) as missing:
        load_msg(catalog, "demo/Nope")
    assert str(missing.value) == f"Cannot locate message [Nope] in package [demo] with paths [['{folder}']]"
    with pytest.raises(MsgNotFoundError, match=r"^Cannot locate message \[Ask\] in package \[demo\]"):
        load_msg(catalog, "demo/Ask")
    with pytest.raises(MsgNotFoundError) as dependency:
        describe_msg(catalog, load_msg(catalog, "demo/Broken"))
    assert str(dependency.value) == f"Cannot locate message [Missing] in package [demo] with paths [['{folder}']]"


def test_malformed_definition_raises_definition_error(tmp_path: Path) -> None:
    package(tmp_path, "bad", {"msg/Bad.msg": "int32 a b\n"})
    catalog = MsgCatalog.from_environment(str(tmp_path))
    with pytest.raises(MsgDefinitionError, match=r"Bad\.msg:1"):
        load_msg(catalog, "bad/Bad")
