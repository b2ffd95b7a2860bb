"""genpy.base, generate_struct, generate_numpy, generator (MsgGenerator/SrvGenerator over
kame's codegen) and message.check_type: the same answers as Debian's real genpy on one request
(tests/libs/genpy_driver.py run by both interpreters)."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

import pytest

from . import debian

DRIVER = Path(__file__).with_name("genpy_driver.py")
STD_MSGS = Path("/usr/share/std_msgs/msg")

REQUEST: dict[str, Any] = {
    "patterns": ["", "i", "iii", "iiiB", "BBdd", "B99d", "%si", "3iB", "BBBBBBBBBBBB"],
    "check_type": [
        ["int8", 127], ["int8", 128], ["int8", -129], ["int8", True], ["int8", 1.0], ["uint8", -1], ["uint8", 255],
        ["uint8", 256], ["uint64", 2**64 - 1], ["uint64", 2**64], ["int64", -(2**63)], ["char", 3], ["byte", -3],
        ["float32", 1], ["float64", "1.0"], ["float64", True], ["bool", 2], ["bool", 1], ["bool", False],
        ["string", "ascii"], ["string", "caf\u00e9"], ["string", {"bytes": "raw"}], ["string", 3],
        ["time", {"time": [1, 2]}], ["time", {"duration": [1, 2]}], ["duration", {"duration": [-1, 2]}],
        ["uint8[]", {"bytes": "xyz"}], ["uint8[]", "text"], ["int32[]", "text"], ["int32[]", {"tuple": [1, 2]}],
        ["int32[3]", [1, 2**40]], ["float64[]", 3], ["std_msgs/String", {"msg": "std_msgs/String"}],
        ["std_msgs/String", {"msg": "std_msgs/Int32"}], ["Header", {"msg": "std_msgs/Header"}],
        ["std_msgs/String", {"msg": "std_msgs/Header"}],
        ["std_msgs/Int8", {"msg": "std_msgs/Int8", "fields": {"data": 300}}],
        ["std_msgs/Header", {"msg": "std_msgs/Header", "fields": {"frame_id": 5}}], ["foo/Bar", 3],
    ],
    "package": {
        "name": "kame_gen_test",
        "msg": {"Reading": "Header header\nfloat64[] values\nuint8[4] tag\nstring from\nint32 KIND=3\n",
                "Pair": "Reading a\nReading b\ntime stamp\n"},
        "srv": {"Measure": "string what\nint32 count\n---\nReading result\nbool ok\n"},
        "search_path": {"std_msgs": [str(STD_MSGS)]},
    },
    "helpers": {
        "registered": {"geometry_msgs/Point": "float64 x\nfloat64 y\nfloat64 z\n",
                       "geometry_msgs/Pose": "Point position\nQuaternion orientation\n",
                       "geometry_msgs/Quaternion": "float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n",
                       "geometry_msgs/PoseStamped": "Header header\nPose pose\n",
                       "geometry_msgs/Span": "time start\nduration length\nPoint[] points\n",
                       "std_msgs/Header": "uint32 seq\ntime stamp\nstring frame_id\n"},
        "pkg_type": [["std_msgs", "String"], ["std_msgs", "geometry_msgs/Point"], ["p", "a/b/c"]],
        "defaults": [[t, "geometry_msgs"] for t in (
            "int8", "char", "byte", "uint64", "float32", "string", "bool", "uint8[]", "uint8[4]", "char[3]",
            "int32[]", "int32[3]", "float64[2]", "string[2]", "bool[1]", "Header", "std_msgs/Header", "time",
            "duration", "time[2]", "Header[2]", "geometry_msgs/Point", "Point", "geometry_msgs/Point[]",
            "geometry_msgs/Point[2]", "Point[2]", "nav_msgs/Path", "Unknown", "Unknown[3]")] + [["Point", "other"]],
        "imports": [["geometry_msgs", t] for t in (
            "int32", "int32[]", "Header", "std_msgs/Header", "time", "duration[]", "geometry_msgs/PoseStamped",
            "PoseStamped", "geometry_msgs/Pose[]", "geometry_msgs/Span", "nav_msgs/Path", "a/b/c")]
            + [["other", "geometry_msgs/Pose"], ["other", "Pose"]],
        "unsafe": "int32 from\nstring self\nfloat64 x\nbool[] import\nint32 class=2\nstring ok=yes\n",
    },
}


def run(python: str) -> dict[str, Any]:
    answer: dict[str, Any] = debian.run(DRIVER, REQUEST, python)
    return answer


def test_genpy_helpers_and_generator_on_kame() -> None:
    ours = run(sys.executable)
    struct = ours["struct"]
    assert struct["reduced"][:6] == ["", "i", "3i", "3iB", "2B2d", "B29d"] and struct["struct_I"] == "<I"
    assert struct["code"][2] == "buff.write(_get_struct_3i().pack(a, b, c))" and struct["patterns"] == ["3i", "2d"]
    checks = dict(zip((f"{t} {json.dumps(v)}" for t, v in REQUEST["check_type"]), ours["check_type"], strict=True))
    assert checks["int8 128"] == "field f exceeds specified width [int8]"
    assert checks['string "caf\\u00e9"'] == "field f is a non-ascii string" and checks["uint8 255"] is None
    generated = ours["generated"]
    assert generated["codes"] == [0, 0] and generated["missing_file_code"] == 1
    assert generated["files"] == ["_Measure.py", "_Pair.py", "_Reading.py"]
    assert generated["Reading"][2] == ["header", "values", "tag", "from_"]  # genpy's keyword rename
    assert generated["bad_package"][0] == "MsgGenerationException"
    helpers = ours["helpers"]
    assert helpers["pkg_type"] == [["std_msgs", "String"], ["geometry_msgs", "Point"], "raises MsgGenerationException"]
    defaults = dict(zip((t for t, _ in REQUEST["helpers"]["defaults"]), helpers["defaults"], strict=False))
    assert defaults["float32"] == "0." and defaults["uint8[4]"] == "b'\\0'*4" and defaults["int32[3]"] == "[0] * 3"
    assert defaults["Point[2]"] == "[geometry_msgs.msg.Point() for _ in range(2)]" and defaults["Unknown"] is None
    assert helpers["imports"][6] == ["import geometry_msgs.msg", "import std_msgs.msg"]  # not Header's time
    assert helpers["safe"][1] == ["from_", "self_", "x", "import_"]
    assert helpers["safe"][2][0][1] == "class_"
    by_functions = ours["by_functions"]
    assert by_functions["Reading"][2] == ["header", "values", "tag", "from_"]
    assert by_functions["Measure"][0] == "kame_gen_test/MeasureRequest"
    assert by_functions["Measure"][4] == generated["Measure"][1]  # the service's md5 as the written module's


@pytest.mark.skipif(not (debian.has("genpy.generator", "std_msgs.msg") and STD_MSGS.is_dir()),
                    reason="Debian's python3-genpy and ros-std-msgs are not installed")
def test_genpy_answers_as_debians_genpy() -> None:
    ours, theirs = run(sys.executable), run(str(debian.SYSTEM_PYTHON))
    assert ours["struct"] == theirs["struct"]
    assert ours["check_type"] == theirs["check_type"]
    assert ours["generated"] == theirs["generated"]
    # a fixed array of an unknown type: genpy fails concatenating None, kame's says None as for the type
    unknown = [t for t, _ in REQUEST["helpers"]["defaults"]].index("Unknown[3]")
    assert (ours["helpers"]["defaults"].pop(unknown), theirs["helpers"]["defaults"].pop(unknown)) == (
        None, "raises TypeError")
    assert ours["helpers"] == theirs["helpers"]
    assert ours["by_functions"] == theirs["by_functions"]
