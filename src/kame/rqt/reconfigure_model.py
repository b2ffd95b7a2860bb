"""rqt_reconfigure's model: the dynamic_reconfigure servers among a master's services, a
server's parameters as rows (group, type, range or choices, description) and the text a user
types for one of them made into the value set_parameters takes. No Qt, no ROS I/O.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from kame.reconfigure.encoding import converted, enum_choices
from kame.reconfigure.errors import DynamicReconfigureParameterException

SET_PARAMETERS = "/set_parameters"


class EditError(ValueError):
    """Typed text that is no value of the parameter."""


@dataclass(frozen=True)
class ParamRow:
    name: str
    type: str  # int, double, str or bool
    group: str  # the group path below the root ("Limits/Inner Most"), "" for the root's own
    description: str
    minimum: Any
    maximum: Any
    default: Any
    choices: tuple[tuple[str, Any], ...]  # (constant name, value) when edited through an enum

    def range_text(self) -> str:
        if self.choices:
            return ", ".join(f"{name}={value}" for name, value in self.choices)
        if self.type in ("int", "double"):
            return f"[{self.minimum}, {self.maximum}]"
        return ""


def servers(service_names: Iterable[str]) -> list[str]:
    """The servers (`/node` for `/node/set_parameters`), as dynamic_reconfigure finds them."""
    return sorted(name[:-len(SET_PARAMETERS)] for name in service_names if name.endswith(SET_PARAMETERS))


def rows(description: Mapping[str, Any]) -> list[ParamRow]:
    """Every parameter of a decoded description tree (kame.reconfigure.encoding.decode_description), depth first."""
    found: list[ParamRow] = []

    def walk(group: Mapping[str, Any], path: str) -> None:
        for param in group.get("parameters", []):
            found.append(ParamRow(param["name"], param["type"], path, param["description"], param["min"],
                                  param["max"], param["default"], tuple(enum_choices(param))))
        for child in group.get("groups", {}).values():
            walk(child, f"{path}/{child['name']}" if path else str(child["name"]))

    walk(description, "")
    return found


def shown(row: ParamRow, value: Any) -> str:
    """A value as its cell shows it: an enum's constant name beside the number."""
    for name, constant in row.choices:
        if constant == value:
            return f"{name} ({value})"
    return str(value)


def parse(row: ParamRow, text: str) -> Any:
    """What the user typed, as the parameter's value: numbers, true/false (yes/no, 1/0), an enum's
    constant by name or value, or "Name (value)" as shown; EditError says why not."""
    text = text.strip()
    if row.choices and text.endswith(")") and " (" in text:
        text = text.rsplit(" (", 1)[0]
    if row.type == "bool" and text.lower() not in ("yes", "true", "t", "1", "no", "false", "f", "0"):
        raise EditError(f"{row.name} is a bool: true or false, not {text!r}")
    for name, constant in row.choices:
        if text.lower() == name.lower():
            return constant
    try:
        value = converted(text, {"name": row.name, "type": row.type, "edit_method": ""})
    except DynamicReconfigureParameterException as exc:
        value = exc
    if row.choices and (isinstance(value, Exception) or value not in [v for _, v in row.choices]):
        raise EditError(f"{row.name} is one of {row.range_text()}, not {text!r}")
    if isinstance(value, Exception):
        raise EditError(str(value))
    return value


def values(rows_: Iterable[ParamRow], config: Mapping[str, Any]) -> dict[str, str]:
    """Each described parameter's value as shown, from a decoded configuration."""
    return {row.name: shown(row, config[row.name]) for row in rows_ if row.name in config}
