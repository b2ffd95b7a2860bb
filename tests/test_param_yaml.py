"""kame.param_yaml: ROS's YAML typing rules for parameters, checks, leaf-by-leaf sets, output text."""

from __future__ import annotations

import math
from typing import Any

import pytest

from kame import param_yaml
from kame.param_yaml import ParamValueError


@pytest.mark.parametrize(("text", "value"), [
    ("010", 8), ("0x10", 16), ("1:30", 90), ("1e3", "1e3"), ("nan", "nan"), ("on", True), ("", ""),
    ("!degrees 180", math.pi), ("deg(90)", math.pi / 2), ("!radians pi/2", math.pi / 2), ("rad(2*pi)", 2 * math.pi),
    ("!radians -pi", -math.pi), ("[deg(180), rad(1)]", [math.pi, 1.0]), ("!!binary aGk=", b"hi"),
])
def test_load(text: str, value: Any) -> None:
    assert param_yaml.load(text) == value


@pytest.mark.parametrize("text", ["!radians __import__('os')", "!radians pi+", "!degrees x", "{a: 1"])
def test_bad_text_is_a_value_error(text: str) -> None:
    with pytest.raises(ParamValueError):
        param_yaml.load(text)


def test_load_all_skips_empty_documents() -> None:
    assert param_yaml.load_all("a: 1\n---\n---\nb: 2\n") == [{"a": 1}, {"b": 2}]


@pytest.mark.parametrize(("value", "problem"), [
    (None, "null"), (2**31, "32-bit"), (-(2**31) - 1, "32-bit"), ({"a": [1, None]}, "null"), ({1: 2}, "string keys"),
    ({1, 2}, "set"),
])
def test_check_refuses_what_the_server_cannot_hold(value: Any, problem: str) -> None:
    with pytest.raises(ParamValueError, match=problem):
        param_yaml.check("/p", value)


def test_check_accepts_server_types() -> None:
    param_yaml.check("/p", {"a": [1, 2.5, "x", True, b"\0"], "b": {"c": 2**31 - 1, "d": -(2**31)}})


def test_leaves_merge_dicts() -> None:
    assert list(param_yaml.leaves("/s", {"a": 1, "b": {"c": "x", "/abs": 2}, "e": {}})) == [
        ("/s/a", 1), ("/s/b/c", "x"), ("/abs", 2)]
    assert list(param_yaml.leaves("/v", [1])) == [("/v", [1])]


def test_verbose_lines_use_python_str() -> None:
    assert param_yaml.verbose_lines({"a": True, "b": {"c": [1, "2"]}}, "/ns") == ["/ns/a=True", "/ns/b/c=[1, '2']"]
    assert param_yaml.verbose_lines(3, "/x") == ["3"]


@pytest.mark.parametrize(("value", "text"), [
    (255, "255\n"), ("hello", "hello\n"), ("1", "'1'\n\n"), (True, "true\n"), ("noetic\n", "'noetic\n\n  '\n\n"),
    ({"b": 1, "a": {"c": [1, 2]}}, "a:\n  c:\n  - 1\n  - 2\nb: 1\n\n"), ("", "''\n\n"),
])
def test_get_text(value: Any, text: str) -> None:
    assert param_yaml.get_text(value) == text


def test_pretty_text() -> None:
    value = {"s": "x\ny", "e": "", "l": [1, 2], "n": 3, "d": {"k": True}}
    assert param_yaml.pretty_text(value) == "d:\n  k: true\ne: \nl: - 1\n- 2\nn: 3\ns: |\n  x\n  y\n"
    assert param_yaml.pretty_text("a\nb") == "a\nb\n"
    assert param_yaml.pretty_text(3) == "3\n"


def test_values_that_contain_themselves_or_nest_too_deep_are_refused() -> None:
    # Each of these used to end in a RecursionError traceback (rosparam load, roslaunch), or, for
    # a deep but finite value, in the master's refusal reported as "Unable to communicate with master!".
    with pytest.raises(ParamValueError, match="a value cannot contain itself"):
        param_yaml.load_all("a: &x [*x]\n")
    with pytest.raises(ParamValueError, match="a value cannot contain itself"):
        param_yaml.load("&x {a: {b: *x}}")
    with pytest.raises(ParamValueError, match="nested more than 50 levels deep"):
        param_yaml.load_all("a: " + "[" * 5000 + "]" * 5000)
    with pytest.raises(ParamValueError, match="nested more than 50 levels deep"):
        param_yaml.load("[" * 100 + "]" * 100)
    cyclic: list[Any] = []
    cyclic.append(cyclic)
    with pytest.raises(ParamValueError, match=r"cannot set parameter \[/a\]: a value cannot contain itself"):
        param_yaml.check("/a", cyclic)
    # shared (not enclosing) aliases and moderate nesting are fine
    nested: list[Any] = []
    for _ in range(48):
        nested = [nested]
    assert param_yaml.load_all("a: &x [1]\nb: *x\nc: " + "[" * 49 + "]" * 49) == [{"a": [1], "b": [1], "c": nested}]
    param_yaml.check("/c", {"c": nested})


def _alias_bomb(levels: int = 9, refs: int = 9, merge: bool = False) -> str:
    """`levels` lines, each referring `refs` times to the one before: refs**levels values once
    expanded, from a few hundred bytes (a "billion laughs")."""
    if merge:
        lines = ["l0: &l0 {" + ", ".join(f"k{i}: {i}" for i in range(refs)) + "}"]
        lines += [f"l{n}: &l{n} {{<<: [{', '.join([f'*l{n - 1}'] * refs)}]}}" for n in range(1, levels)]
    else:
        lines = ["l0: &l0 [" + ", ".join(['"lol"'] * refs) + "]"]
        lines += [f"l{n}: &l{n} [{', '.join([f'*l{n - 1}'] * refs)}]" for n in range(1, levels)]
    return "\n".join(lines) + "\n"


def test_an_alias_bomb_is_refused_when_loaded() -> None:
    # It used to hang the shape check (and every later walk) for good: 9**9 leaves.
    with pytest.raises(ParamValueError, match=r"YAML aliases expand this value to \d+ values"):
        param_yaml.load_all(_alias_bomb())
    with pytest.raises(ParamValueError, match="YAML aliases expand"):
        param_yaml.load("{" + _alias_bomb().strip().replace("\n", ", ") + "}")  # one argument
    with pytest.raises(ParamValueError, match="YAML aliases expand"):
        param_yaml.safe_load(_alias_bomb())
    with pytest.raises(ParamValueError, match="YAML aliases expand"):
        param_yaml.check("/bomb", param_yaml.BoundedLoader(_alias_bomb()).get_single_data())
    # moderate sharing is fine: 4 levels of 9 (6,561 values)
    assert len(param_yaml.load_all(_alias_bomb(levels=4))[0]["l3"]) == 9


def test_nested_merge_keys_stay_linear() -> None:
    value = param_yaml.load_all(_alias_bomb(merge=True))[0]
    assert value["l8"] == {f"k{i}": i for i in range(9)}
