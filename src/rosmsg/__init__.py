"""rosmsg as a library: message and service definitions as `rosmsg show` prints them
(`rosmsg.get_msg_text('geometry_msgs/Pose')`), the types of a package, and a message as the
YAML `rosmsg-proto` and rqt's tools write. The `rosmsg` command is kame.cli.rosmsg; both
describe types with kame.msg.describe, from the packages on ROS_PACKAGE_PATH and kame's own.

One difference: upstream's get_yaml_for_msg fails on `time_offset` (a NameError); here the
offset is subtracted from each Time field, as its documentation says.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

import yaml

from kame.msg import lookup
from kame.msg.catalog import MsgCatalog
from kame.msg.describe import Kind, describe_msg, describe_srv, load_msg, load_srv, types_in_package
from kame.msg.errors import MessageError
from kame.msg.message import Message
from kame.rostime import Time, TVal
from rospkg import ResourceNotFound, get_ros_paths

__all__ = ["MAX_DEFAULT_NON_FLOW_ITEMS", "MODE_MSG", "MODE_SRV", "ROSMsgException", "create_names_filter",
           "get_array_type_instance", "get_msg_text", "get_srv_text", "get_yaml_for_msg", "list_msgs", "list_srvs",
           "list_types"]

MODE_MSG = ".msg"
MODE_SRV = ".srv"
# a mapping or list longer than this is written in the caller's flow style (default: pyyaml's)
MAX_DEFAULT_NON_FLOW_ITEMS = 4
_ZEROS: dict[str, Any] = {**dict.fromkeys(("byte", "int8", "int16", "int32", "int64", "char", "uint8", "uint16",
                                           "uint32", "uint64", "float32", "float64"), 0),
                          "string": "", "bool": False}
_STD_TYPES = {"time": "std_msgs/Time", "duration": "std_msgs/Duration", "Header": "std_msgs/Header"}


class ROSMsgException(Exception):
    """A type that cannot be found or read."""


def get_msg_text(type_: str, raw: bool = False, rospack: Any = None) -> str:
    """The message type's fields, nested types expanded (`raw`: the .msg file's text)."""
    try:
        catalog = MsgCatalog.from_environment()
        msg = load_msg(catalog, type_)
        return msg.text if raw else describe_msg(catalog, msg)
    except MessageError as exc:
        raise ROSMsgException(f"Unable to load msg [{type_}]: {exc}") from None


def get_srv_text(type_: str, raw: bool = False, rospack: Any = None) -> str:
    """The service type's request and response, `---` between (`raw`: the .srv file's text)."""
    try:
        catalog = MsgCatalog.from_environment()
        srv = load_srv(catalog, type_)
        return srv.text if raw else describe_srv(catalog, srv)
    except MessageError as exc:
        raise ROSMsgException(f"Unknown srv type [{type_}]: {exc}") from None


def list_types(package: str, mode: str = MODE_MSG, rospack: Any = None) -> list[str]:
    """`pkg/Type` of each message (MODE_MSG) or service (MODE_SRV) of `package`, sorted;
    ResourceNotFound when there is no such package."""
    if mode not in (MODE_MSG, MODE_SRV):
        raise ValueError(f"Unknown mode for list_types: {mode}")
    catalog = MsgCatalog.from_environment()
    if package not in catalog.packages:
        raise ResourceNotFound(package, ros_paths=get_ros_paths())
    return types_in_package(catalog, package, Kind.MSG if mode == MODE_MSG else Kind.SRV)


def list_msgs(package: str, rospack: Any = None) -> list[str]:
    """`pkg/Type` of each message of `package`, sorted."""
    return list_types(package, MODE_MSG, rospack)


def list_srvs(package: str, rospack: Any = None) -> list[str]:
    """`pkg/Type` of each service of `package`, sorted."""
    return list_types(package, MODE_SRV, rospack)


def get_array_type_instance(field_type: str, default_package: str | None = None) -> Any:
    """A default element of an array field's type (0, '', False or a message; time and duration
    as std_msgs' Time and Duration messages), or None when the type is unknown."""
    base = field_type.strip().rstrip("[]")
    if base == "empty":
        return None
    if "/" not in base:
        if base in _ZEROS:
            return _ZEROS[base]
        if base in _STD_TYPES:
            base = _STD_TYPES[base]
        elif default_package is None:
            return None
        else:
            base = f"{default_package}/{base}"
    msg_class = lookup.message_class(base)
    return None if msg_class is None else msg_class()


def create_names_filter(names: Iterable[str]) -> Callable[[Any], list[str]]:
    """A field_filter for get_yaml_for_msg leaving out the fields in `names`."""
    excluded = set(names)
    return lambda obj: [slot for slot in obj.__slots__ if slot not in excluded]


def get_yaml_for_msg(msg: Any, prefix: str = "", time_offset: Time | None = None, current_time: Time | None = None,
                     field_filter: Callable[[Any], Iterable[str]] | None = None, flow_style_: bool | None = None,
                     fill_arrays_: bool = False) -> str:
    """`msg` (a message, or a list or dict of them) as YAML, each line after `prefix`: fields in
    name order, in block style until a message with more than MAX_DEFAULT_NON_FLOW_ITEMS fields
    or a longer list switches the rest to `flow_style_` (None: pyyaml's choice, flow for
    mappings of scalars), as upstream's heuristic does. `fill_arrays_`: an empty variable-length
    array gets one default element (for completion). `current_time` is unused, as upstream."""

    class Dumper(yaml.SafeDumper):
        pass

    def to_callers_style(dumper: Any) -> None:
        dumper.default_flow_style = flow_style_  # None too: pyyaml's heuristic, though its stubs say bool

    def represent(dumper: yaml.SafeDumper, obj: Any) -> yaml.Node:
        if isinstance(obj, TVal):
            names: list[str] = ["secs", "nsecs"]
            slot_types: list[str] = ["int32", "int32"]
        else:
            names = list(field_filter(obj)) if field_filter is not None else list(obj.__slots__)
            slot_types = list(obj._slot_types)
        fields: dict[str, Any] = {}
        for index, key in enumerate(names):
            if key.startswith("_"):
                continue
            val = getattr(obj, key)
            if type(val) is list and len(val) > MAX_DEFAULT_NON_FLOW_ITEMS:
                to_callers_style(dumper)
            if time_offset is not None and isinstance(val, Time):
                fields[key] = val - time_offset
            elif fill_arrays_ and type(val) is list and not val:
                instance = get_array_type_instance(slot_types[index], obj._type.partition("/")[0])
                fields[key] = val if instance is None else [instance]
            else:
                fields[key] = val
        if len(fields) > MAX_DEFAULT_NON_FLOW_ITEMS:
            to_callers_style(dumper)
        return dumper.represent_dict(fields)

    Dumper.add_multi_representer(Message, represent)
    Dumper.add_multi_representer(TVal, represent)
    # False, not None, at the top: pyyaml would bracket a small message ({data: 0})
    text = yaml.dump(msg, Dumper=Dumper, default_flow_style=flow_style_ is True, default_style="")
    if prefix:
        return prefix + ("\n" + prefix).join(text.splitlines())
    return text.rstrip("\n")
