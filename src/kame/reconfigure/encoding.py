"""dynamic_reconfigure's config codec (its encoding module): Config dicts to and from the messages.

A Config is a dict whose keys read as attributes too (config.int_param), as servers'
callbacks use it. Descriptions are the trees a generated <Name>Config module holds.
"""

from __future__ import annotations

import ast
import copy
from typing import Any

from dynamic_reconfigure.msg import (
    BoolParameter,
    DoubleParameter,
    GroupState,
    IntParameter,
    ParamDescription,
    StrParameter,
)
from dynamic_reconfigure.msg import Config as ConfigMsg
from dynamic_reconfigure.msg import ConfigDescription as ConfigDescrMsg
from dynamic_reconfigure.msg import Group as GroupMsg
from kame.reconfigure.errors import DynamicReconfigureParameterException


class Config(dict[str, Any]):
    """A dict whose items are attributes too."""

    def __getattr__(self, name: str) -> Any:
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None

    def __setattr__(self, name: str, value: Any) -> None:
        self[name] = value

    def copy(self) -> Config:
        return Config(self)

    def __deepcopy__(self, memo: dict[int, Any]) -> Config:
        return Config({copy.deepcopy(k, memo): copy.deepcopy(v, memo) for k, v in self.items()})


def extract_params(group: dict[str, Any]) -> list[dict[str, Any]]:
    """Every parameter of a description tree (groups as a list or as a dict by name), depth first."""
    params = list(group["parameters"])
    children = group["groups"]
    for child in children.values() if isinstance(children, dict) else children:
        params.extend(extract_params(child))
    return params


def encode_groups(group: dict[str, Any]) -> list[Any]:
    msg = GroupMsg(name=group["name"], type=group["type"], id=group["id"], parent=group["parent"],
                   parameters=[ParamDescription(p["name"], p["type"], p["level"], p["description"], p["edit_method"])
                               for p in group["parameters"]])
    groups = [msg]
    for child in group["groups"]:
        groups.extend(encode_groups(child))
    return groups


def encode_description(config_type: Any) -> Any:
    """The ConfigDescription of a generated <Name>Config module."""
    return ConfigDescrMsg(groups=encode_groups(config_type.config_description), max=encode_config(config_type.max),
                          min=encode_config(config_type.min), dflt=encode_config(config_type.defaults))


def _group_states(group: dict[str, Any]) -> list[Any]:
    states = []
    for child in group["groups"].values():
        states.extend(_group_states(child))
        states.append(GroupState(child["name"], child["state"], child["id"], child["parent"]))
    return states


def encode_config(config: dict[str, Any]) -> Any:
    """A Config message: each value by its Python type; a "groups" tree as its group states."""
    msg = ConfigMsg()
    for name, value in config.items():
        if type(value) is bool:
            msg.bools.append(BoolParameter(name, value))
        elif type(value) is int:
            msg.ints.append(IntParameter(name, value))
        elif type(value) is str:
            msg.strs.append(StrParameter(name, value))
        elif type(value) is float:
            msg.doubles.append(DoubleParameter(name, value))
        elif isinstance(value, dict):
            msg.groups.append(GroupState(value["name"], value["state"], value["id"], value["parent"]))
            msg.groups.extend(_group_states(value))
    return msg


def group_dict(group: Any) -> Config:
    return Config({"id": group.id, "parent": group.parent, "name": group.name, "type": getattr(group, "type", ""),
                   "state": getattr(group, "state", True), "groups": Config({}), "parameters": Config({})})


def get_tree(msg: Any, group: Any = None) -> Config:
    """The group tree of a Config or ConfigDescription message, by name, from the root group (id 0)."""
    root = group is None
    if group is None:
        group = next(g for g in msg.groups if g.id == 0)
    children = Config({})
    for child in msg.groups:
        if child.id != 0 and child.parent == group.id:
            node = group_dict(child)
            node["groups"] = get_tree(msg, child)
            children[node["name"]] = node
    if not root:
        return children
    tree = group_dict(group)
    tree["groups"] = children
    return tree


def _fill_parameters(config: Config, tree: dict[str, Any], description: dict[str, Any], in_parameters: bool) -> None:
    for param in description["parameters"]:
        if param["name"] in config:
            (tree["parameters"] if in_parameters else tree)[param["name"]] = config[param["name"]]
    described = description["groups"]
    for child in tree["groups"].values():
        for child_description in described.values() if isinstance(described, dict) else described:
            if child_description["name"] == child["name"]:
                _fill_parameters(config, child, child_description, in_parameters)


def _values(msg: Any) -> Config:
    return Config((p.name, p.value) for p in [*msg.bools, *msg.ints, *msg.strs, *msg.doubles])


def decode_config(msg: Any, description: dict[str, Any] | None = None) -> Config:
    """A Config from a Config message; with the description, its "groups" tree too, each group
    holding its parameters' values beside its own keys (as dynamic_reconfigure's decode_config)."""
    config = _values(msg)
    if msg.groups and description is not None:
        config["groups"] = get_tree(msg)
        _fill_parameters(config, config["groups"], description, in_parameters=False)
    return config


def initial_config(msg: Any, description: dict[str, Any] | None = None) -> Config:
    """A server's first Config: as decode_config, but each group's values under its "parameters"."""
    config = _values(msg)
    if msg.groups and description is not None:
        config["groups"] = get_tree(msg)
        _fill_parameters(config, config["groups"], description, in_parameters=True)
    return config


def decode_description(msg: Any) -> dict[str, Any]:
    """The description tree (groups by name, parameters with min, max and default) of a ConfigDescription."""
    mins, maxes, defaults = decode_config(msg.min), decode_config(msg.max), decode_config(msg.dflt)

    def params(group: Any) -> list[dict[str, Any]]:
        return [{"name": p.name, "min": mins[p.name], "max": maxes[p.name], "default": defaults[p.name],
                 "type": p.type, "level": p.level, "description": p.description, "edit_method": p.edit_method}
                for p in group.parameters]

    def children(parent: dict[str, Any]) -> Config:
        found = Config({})
        for group in msg.groups:
            if group.id != 0 and group.parent == parent["id"]:
                node = group_dict(group)
                node["parameters"] = params(group)
                node["groups"] = children(node)
                found[node["name"]] = node
        return found

    root_msg = next((g for g in msg.groups if g.id == 0), None)
    if root_msg is None:
        return {}
    root = group_dict(root_msg)
    root["parameters"] = params(root_msg)
    root["groups"] = children(root)
    return root


_TYPES: dict[str, type] = {"int": int, "double": float, "str": str, "bool": bool}


def enum_choices(param: dict[str, Any]) -> list[tuple[str, Any]]:
    """The (name, value) constants of a parameter edited through an enum, else []."""
    if not param.get("edit_method"):
        return []
    return [(str(c["name"]), _TYPES[c["type"]](c["value"])) for c in ast.literal_eval(param["edit_method"])["enum"]]


def converted(value: Any, param: dict[str, Any]) -> Any:
    """`value` as parameter `param` takes it: bools from yes/true/t/1, enum constants by name, else the type's own."""
    target = _TYPES[param["type"]]
    if target is bool and isinstance(value, str):
        return value.lower() in ("yes", "true", "t", "1")
    if isinstance(value, str):
        for name, constant in enum_choices(param):
            if value.lower() == name.lower():
                return constant
    try:
        return target(value)
    except ValueError as exc:
        raise DynamicReconfigureParameterException(
            f"can't set parameter '{param['name']}' of {target}: {exc}") from None
