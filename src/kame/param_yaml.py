"""Parameter values as YAML, with ROS's typing rules (rosparam, roslaunch `<rosparam>`, `_p:=v`).

Rules (ros1-user-behaviour spec §7, as the rosparam library behaves):
- Text is read with PyYAML's safe loader (YAML 1.1): `010` is octal, `1:30` sexagesimal, `1e3`
  and `nan` stay strings, `yes`/`on` are true. `!!binary` gives bytes (XML-RPC base64).
- `!degrees X`, `deg(X)` become X·π/180 and `!radians EXPR`, `rad(EXPR)` become EXPR, where EXPR
  is arithmetic over numbers and `pi` (evaluated here without eval()).
- The parameter server holds bool, 32-bit int, double, string, binary, list and string-keyed
  dict. Anything else (null, dates, sets, wider ints) is refused before anything is sent.
- Values nest at most MAX_NESTING containers deep (the master's XML-RPC reader refuses much
  deeper ones) and never contain themselves (a YAML alias to an enclosing node): both are
  refused with a clear error, as YAML nested too deeply for the parser is.
- Aliases are shared, not copied, when YAML is loaded; every later walk (checks, XML-RPC,
  setting leaf by leaf) expands them. A value whose aliases add more than MAX_ALIAS_EXPANSION
  values once expanded (nine levels of nine references: 387 million) is refused when loaded;
  the checks walk each shared container once, so they take time linear in the text. Merge
  keys (`<<: *a`) keep one entry per key as they are merged, so nested merges stay linear too.
- A dict is set leaf by leaf (it merges into an existing namespace); an empty dict sets nothing.
- Output is PyYAML block style with sorted keys, the way `rosparam get/dump` print it.
Pure: text and values in, values and text out.
"""

from __future__ import annotations

import ast
import datetime
import math
import operator
import re
from collections.abc import Callable, Iterator
from typing import Any

import yaml

from kame import names

MAX_INT = 2**31 - 1
MIN_INT = -(2**31)
#: Deepest nesting of lists and dicts a parameter value may have.
MAX_NESTING = 50
#: How many values YAML aliases may add to a value once it is expanded.
MAX_ALIAS_EXPANSION = 100_000


class ParamValueError(ValueError):
    """A value the parameter server cannot hold, or YAML text that does not load."""


# ------------------------------------------------------------------ angles

_BINOPS: dict[type[ast.operator], Callable[[float, float], float]] = {
    ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv,
    ast.Pow: operator.pow, ast.Mod: operator.mod,
}


def _arith(node: ast.AST) -> float:
    if isinstance(node, ast.Expression):
        return _arith(node.body)
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool):
        return float(node.value)
    if isinstance(node, ast.Name) and node.id == "pi":
        return math.pi
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        value = _arith(node.operand)
        return -value if isinstance(node.op, ast.USub) else value
    if isinstance(node, ast.BinOp) and type(node.op) in _BINOPS:
        return _BINOPS[type(node.op)](_arith(node.left), _arith(node.right))
    raise ValueError("not arithmetic")


def radians(text: str) -> float:
    """`pi/2`, `rad(2*pi)`, `1.5` -> radians."""
    expr = text.strip()
    if expr.startswith("rad(") and expr.endswith(")"):
        expr = expr[4:-1]
    try:
        return _arith(ast.parse(expr, mode="eval"))
    except (SyntaxError, ValueError, ZeroDivisionError, OverflowError):
        raise ParamValueError(f"invalid radian expression: {text}") from None


def degrees(text: str) -> float:
    """`180`, `deg(90)` -> radians."""
    expr = text.strip()
    if expr.startswith("deg(") and expr.endswith(")"):
        expr = expr[4:-1]
    try:
        return float(expr) * math.pi / 180.0
    except ValueError:
        raise ParamValueError(f"invalid degree value: {text}") from None


class BoundedLoader(yaml.SafeLoader):
    """SafeLoader whose merge keys keep one entry per key (the last, which is the one that
    counts): merging a mapping that merges others then costs its keys, not their product.
    Recent PyYAML releases do this themselves; older ones that our pin allows copy every
    merged pair, which nested merges make exponential."""

    def flatten_mapping(self, node: yaml.MappingNode) -> None:
        super().flatten_mapping(node)
        last: dict[tuple[str, str], int] = {}
        for i, (key, _) in enumerate(node.value):
            if isinstance(key, yaml.ScalarNode):
                last[(key.tag, key.value)] = i
        if len(last) < len(node.value):
            node.value = [pair for i, pair in enumerate(node.value)
                          if not isinstance(pair[0], yaml.ScalarNode) or last[(pair[0].tag, pair[0].value)] == i]


class ParamLoader(BoundedLoader):
    """SafeLoader plus rosparam's angle tags and their `deg(...)`/`rad(...)` shorthands."""


def _construct_radians(loader: yaml.SafeLoader, node: yaml.Node) -> float:
    return radians(str(loader.construct_scalar(node)))  # type: ignore[arg-type]


def _construct_degrees(loader: yaml.SafeLoader, node: yaml.Node) -> float:
    return degrees(str(loader.construct_scalar(node)))  # type: ignore[arg-type]


ParamLoader.add_constructor("!radians", _construct_radians)
ParamLoader.add_constructor("!degrees", _construct_degrees)
ParamLoader.add_implicit_resolver("!degrees", re.compile(r"^deg\([^\)]*\)$"), ["d"])
ParamLoader.add_implicit_resolver("!radians", re.compile(r"^rad\([^\)]*\)$"), ["r"])


def load(text: str) -> Any:
    """One YAML value (a command-line argument); the empty text is the empty string."""
    if text == "":
        return ""
    try:
        value = yaml.load(text, Loader=ParamLoader)
    except yaml.YAMLError as exc:
        raise ParamValueError(f"invalid YAML: {_one_line(exc)}") from None
    except RecursionError:
        raise ParamValueError(_TOO_DEEP) from None
    check_shape(value)
    return value


def load_all(text: str) -> list[Any]:
    """Every document of a YAML file, empty documents left out."""
    try:
        documents = [doc for doc in yaml.load_all(text, Loader=ParamLoader) if doc is not None]
    except yaml.YAMLError as exc:
        raise ParamValueError(f"invalid YAML: {_one_line(exc)}") from None
    except RecursionError:
        raise ParamValueError(_TOO_DEEP) from None
    for doc in documents:
        check_shape(doc)
    return documents


def safe_load(text: str) -> Any:
    """PyYAML's safe_load (yaml.YAMLError for text that is not YAML), refusing with
    ParamValueError values that nest too deeply, contain themselves or expand through aliases
    past MAX_ALIAS_EXPANSION: for command-line arguments, whose tools word YAML errors their way."""
    try:
        value = yaml.load(text, Loader=BoundedLoader)
    except RecursionError:
        raise ParamValueError(_TOO_DEEP) from None
    check_shape(value)
    return value


def _one_line(exc: yaml.YAMLError) -> str:
    return " ".join(str(exc).split())


_TOO_DEEP = f"invalid YAML: nested more than {MAX_NESTING} levels deep"
_SELF = "a value cannot contain itself (a YAML alias refers to a node that encloses it)"


def check_shape(value: Any) -> None:
    """Raise ParamValueError if `value` contains itself, nests deeper than MAX_NESTING or expands
    through shared (aliased) containers past MAX_ALIAS_EXPANSION values: what every walk over
    it, and the XML-RPC encoding, would otherwise fail on with RecursionError or never finish."""
    problem = _shape_problem(value)
    if problem:
        raise ParamValueError(problem)


def _shape_problem(value: Any) -> str | None:
    shape = _Shape()
    try:
        expanded, _ = shape.measure(value, 0)
    except _ShapeError as exc:
        return str(exc)
    if expanded - shape.distinct > MAX_ALIAS_EXPANSION:
        return (f"YAML aliases expand this value to {expanded} values, more than "
                f"{MAX_ALIAS_EXPANSION} beyond the {shape.distinct} written")
    return None


class _ShapeError(Exception):
    pass


class _Shape:
    """One walk over the distinct containers of a value (a shared one is measured once)."""

    def __init__(self) -> None:
        self.measured: dict[int, tuple[int, int]] = {}  # id -> (values once expanded, height)
        self.enclosing: set[int] = set()
        self.distinct = 0

    def measure(self, value: Any, depth: int) -> tuple[int, int]:
        if isinstance(value, dict):
            items: Any = value.values()
        elif isinstance(value, (list, tuple)):
            items = value
        else:
            self.distinct += 1
            return 1, 0
        key = id(value)
        known = self.measured.get(key)
        if known is None:
            if key in self.enclosing:
                raise _ShapeError(_SELF)
            if depth >= MAX_NESTING:
                raise _ShapeError(_NESTED)
            self.enclosing.add(key)
            self.distinct += 1
            size, height = 1, 0
            for item in items:
                item_size, item_height = self.measure(item, depth + 1)
                size += item_size
                height = max(height, item_height + 1)
            self.enclosing.discard(key)
            known = self.measured[key] = (size, height)
        elif depth + known[1] >= MAX_NESTING:
            raise _ShapeError(_NESTED)
        return known


_NESTED = f"values nested more than {MAX_NESTING} levels deep cannot be stored"


# ------------------------------------------------------------------ what the server can hold


def check(name: str, value: Any) -> None:
    """Raise ParamValueError if `value` (to be stored at `name`) cannot go to the parameter server."""
    problem = _shape_problem(value) or _problem(value, set())
    if problem:
        raise ParamValueError(f"cannot set parameter [{name}]: {problem}")


def _problem(value: Any, checked: set[int]) -> str | None:
    """What the parameter server cannot hold in `value` (each shared container looked at once)."""
    if isinstance(value, bool) or isinstance(value, (float, str, bytes)):
        return None
    if isinstance(value, int):
        if not MIN_INT <= value <= MAX_INT:
            return f"{value} does not fit a 32-bit signed integer (int exceeds XML-RPC limits)"
        return None
    if value is None:
        return "the parameter server cannot hold null (~ or null); quote it to store a string"
    if isinstance(value, (datetime.date, datetime.datetime)):
        return f"the parameter server cannot hold a date ({value}); quote it to store a string"
    if isinstance(value, (list, tuple, dict)):
        if id(value) in checked:
            return None
        checked.add(id(value))
    if isinstance(value, (list, tuple)):
        for item in value:
            problem = _problem(item, checked)
            if problem:
                return problem
        return None
    if isinstance(value, dict):
        for key, item in value.items():
            if not isinstance(key, str):
                return f"YAML dictionaries must have string keys, not {key!r}"
            problem = _problem(item, checked)
            if problem:
                return problem
        return None
    return f"the parameter server cannot hold a {type(value).__name__} ({value!r})"


def leaves(name: str, value: Any) -> Iterator[tuple[str, Any]]:
    """The (name, value) pairs a set of `value` at `name` makes: dicts are merged key by key."""
    if isinstance(value, dict):
        for key, item in value.items():
            yield from leaves(names.ns_join(name, key), item)
    else:
        yield name, value


def verbose_lines(value: Any, ns: str) -> list[str]:
    """`ns/key=value` per leaf, as `rosparam load -v` and `dump -v` print them (Python str())."""
    if not isinstance(value, dict):
        return [str(value)]
    lines: list[str] = []
    for key, item in value.items():
        if isinstance(item, dict):
            lines.extend(verbose_lines(item, names.ns_join(ns, key)))
        else:
            lines.append(f"{names.ns_join(ns, key)}={item}")
    return lines


# ------------------------------------------------------------------ output


def dump(value: Any) -> str:
    """PyYAML block style with sorted keys (what `rosparam dump` writes)."""
    return yaml.safe_dump(value, default_flow_style=False, allow_unicode=False)


def get_text(value: Any) -> str:
    """What `rosparam get` prints: the YAML dump without the `...` end marker, then a newline."""
    text = dump(value)
    if text.endswith("\n...\n"):
        text = text[:-5]
    return text + "\n"


def pretty_text(value: Any) -> str:
    """What `rosparam get -p` prints (readable, not YAML-safe)."""
    if isinstance(value, dict):
        out: list[str] = []
        _pretty(value, "", out)
        return "".join(out)
    if isinstance(value, str):
        return value + "\n"
    return get_text(value)


def _pretty(value: dict[str, Any], indent: str, out: list[str]) -> None:
    for key in sorted(value):
        item = value[key]
        if isinstance(item, dict):
            out.append(f"{indent}{key}:\n")
            _pretty(item, indent + "  ", out)
        elif isinstance(item, str):
            if "\n" in item:
                out.append(f"{indent}{key}: |\n")
                out.extend(f"{indent}  {line}\n" for line in item.split("\n"))
            else:
                out.append(f"{indent}{key}: {item}\n")
        else:
            text = dump(item)
            if text.endswith("\n...\n"):
                text = text[:-4]
            out.append(f"{indent}{key}: {text}")
