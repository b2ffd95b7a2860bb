"""Properties of the text formats users write: launch XML and YAML parameters load or are
refused with the format's own error, never anything else; parameter values round-trip
through their YAML dump."""

from __future__ import annotations

import math
from typing import Any

import yaml
from hypothesis import given
from hypothesis import strategies as st

from kame import param_yaml
from kame.launch.errors import LaunchError
from kame.launch.xmltree import parse

_TAGS = st.sampled_from(["launch", "node", "param", "rosparam", "group", "arg", "include", "remap", "env"])
_ATTRS = st.dictionaries(st.sampled_from(["name", "pkg", "type", "value", "if", "ns", "file"]),
                         st.text(st.characters(exclude_categories=("Cs", "Cc")), max_size=8), max_size=3)


def _element(depth: int) -> st.SearchStrategy[str]:
    def render(tag: str, attrs: dict[str, str], children: list[str]) -> str:
        from xml.sax.saxutils import quoteattr

        head = tag + "".join(f" {k}={quoteattr(v)}" for k, v in attrs.items())
        return f"<{head}>{''.join(children)}</{tag}>" if children else f"<{head}/>"

    kids = st.lists(_element(depth - 1), max_size=3) if depth else st.just([])
    return st.builds(render, _TAGS, _ATTRS, kids)


@given(xml=_element(3))
def test_well_formed_launch_xml_parses_to_its_elements(xml: str) -> None:
    assert parse(xml, "fuzz.launch").toxml() == xml  # the tree holds every element and attribute


@given(junk=st.binary(max_size=100) | _element(2).map(lambda x: x[: len(x) // 2].encode()))
def test_any_bytes_parse_as_launch_xml_or_say_why(junk: bytes) -> None:
    try:
        parse(junk, "fuzz.launch")
    except LaunchError:
        pass


@given(text=st.text(max_size=80))
def test_any_text_loads_as_parameters_or_says_why(text: str) -> None:
    for load in (param_yaml.load, param_yaml.load_all):
        try:
            load(text)
        except param_yaml.ParamValueError:
            pass
    try:
        param_yaml.safe_load(text)  # command-line arguments: the caller words YAML errors itself
    except (param_yaml.ParamValueError, yaml.YAMLError):
        pass


_KEYS = st.from_regex(r"[a-z][a-z0-9_]{0,5}", fullmatch=True)
_PARAMS: st.SearchStrategy[Any] = st.recursive(
    st.integers(param_yaml.MIN_INT, param_yaml.MAX_INT) | st.booleans() | st.text(max_size=10)
    | st.floats(allow_nan=False),
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(_KEYS, inner, max_size=3), max_leaves=10)


@given(value=_PARAMS)
def test_parameter_values_round_trip_through_their_dump(value: Any) -> None:
    param_yaml.check("/p", value)
    back = param_yaml.load(param_yaml.dump(value))
    assert back == value or (isinstance(value, float) and math.isinf(value) and back == value)


@given(levels=st.integers(2, 12), refs=st.integers(2, 12))
def test_aliases_are_refused_exactly_when_they_expand_too_far(levels: int, refs: int) -> None:
    lines = ["l0: &l0 [" + ", ".join(["x"] * refs) + "]"]
    lines += [f"l{n}: &l{n} [{', '.join([f'*l{n - 1}'] * refs)}]" for n in range(1, levels)]
    sizes = [1 + refs]  # each line's list once expanded: itself and what it holds
    for _ in range(1, levels):
        sizes.append(1 + refs * sizes[-1])
    expanded = 1 + sum(sizes)  # and the root mapping
    written = 1 + levels + refs  # the root, each line's list, the first line's values
    try:
        param_yaml.load_all("\n".join(lines))
    except param_yaml.ParamValueError as exc:
        assert "YAML aliases expand" in str(exc)
        assert expanded - written > param_yaml.MAX_ALIAS_EXPANSION
    else:
        assert expanded - written <= param_yaml.MAX_ALIAS_EXPANSION
