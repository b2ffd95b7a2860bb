"""Typing of <param> values and boolean attributes, as roslaunch does it (not rosparam's rules).

Rules (roslaunch loader.convert_value):
- "auto" (no type): text with a `.` that float() reads is a double; text without `_` that int()
  reads is an int (`010` is 10, surrounding spaces allowed); `true`/`false` in any case are
  bools; anything else stays a string (`0x10`, `1e3`, `yes`, `nan`, `[1, 2]`).
- str/string keep the text; int/double convert or fail; bool/boolean take true/false/1/0
  (any case, spaces trimmed); yaml is PyYAML's safe_load of the text.
"""

from __future__ import annotations

from typing import Any

import yaml

from kame import param_yaml


def convert_value(value: str, type_: str) -> Any:
    kind = type_.lower()
    if kind == "auto":
        try:
            if "." in value:
                return float(value)
            if "_" not in value:
                return int(value)
        except ValueError:
            pass
        if value.lower() in ("true", "false"):
            return convert_value(value, "bool")
        return value
    if kind in ("str", "string"):
        return value
    if kind == "int":
        return int(value)
    if kind == "double":
        return float(value)
    if kind in ("bool", "boolean"):
        text = value.lower().strip()
        if text in ("true", "1"):
            return True
        if text in ("false", "0"):
            return False
        raise ValueError(f"{text} is not a '{type_}' type")
    if kind == "yaml":
        try:
            return param_yaml.safe_load(value)
        except (yaml.YAMLError, param_yaml.ParamValueError) as exc:
            raise ValueError(str(exc)) from exc
    raise ValueError(f"Unknown type '{type_}'")


def bool_attr(value: str | None, default: bool, label: str) -> bool:
    """A true/false attribute (respawn, required, clear_params, ...)."""
    if value is None:
        return default
    if value.lower() == "true":
        return True
    if value.lower() == "false":
        return False
    if not value:
        raise ValueError(f"bool value for {label} must be non-empty")
    raise ValueError(f"invalid bool value for {label}: {value}")


def float_attr(value: str | None, default: float, label: str) -> float:
    if value is None:
        return default
    if not value:
        raise ValueError(f"bool value for {label} must be non-empty")
    try:
        return float(value)
    except ValueError:
        raise ValueError(f"invalid float value for {label}: {value}") from None
