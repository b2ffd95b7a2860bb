"""rosmsg as a library: message and service definitions as `rosmsg show` prints them
(`rosmsg.get_msg_text('geometry_msgs/Pose')`), the types of a package, and a message as the
YAML `rosmsg-proto` and rqt's tools write. The `rosmsg` command is kame.cli.rosmsg; both
describe types with kame.msg.describe, from the packages on ROS_PACKAGE_PATH and kame's own.

One difference: upstream's get_yaml_for_msg fails on `time_offset` (a NameError); here the
offset is subtracted from each Time field, as its documentation says.
"""

from __future__ import annotations

import collections
import inspect
import os
import sys
from collections.abc import Callable, Iterable, Iterator, Sequence
from io import StringIO
from optparse import OptionParser
from typing import Any

import yaml

import roslib
import roslib.message
import rospkg
from genpy.dynamic import generate_dynamic
from kame.catkin.find_in_workspaces import find_in_workspaces
from kame.cli import rosmsg as _command
from kame.msg import lookup
from kame.msg.catalog import MsgCatalog
from kame.msg.describe import Kind, describe_msg, describe_srv, load_msg, load_srv, types_in_package
from kame.msg.errors import MessageError
from kame.msg.message import Message
from kame.rostime import Time, TVal
from rospkg import ResourceNotFound, get_ros_paths

# what `from rosmsg import *` gives with ROS's rosmsg (which has no __all__: every public name,
# the modules it imports too), but for the genmsg module (README, "ROS Python modules: names not provided")
__all__ = ["MAX_DEFAULT_NON_FLOW_ITEMS", "MODE_MSG", "MODE_SRV", "OptionParser", "ROSMsgException",
           "RosMsgProtoArgsException", "RosMsgProtoException", "StringIO", "collections",
           "construct_ordered_mapping", "construct_yaml_map_with_ordered_dict", "create_names_filter",
           "find_in_workspaces", "fullusage", "generate_dynamic", "get_array_type_instance", "get_msg_text",
           "get_srv_text", "get_yaml_for_msg", "init_rosmsg_proto", "inspect", "iterate_packages", "list_msgs",
           "list_srvs", "list_types", "os", "represent_ordered_mapping", "roslib", "rosmsg_cmd_list",
           "rosmsg_cmd_md5", "rosmsg_cmd_package", "rosmsg_cmd_packages", "rosmsg_cmd_prototype", "rosmsg_cmd_show",
           "rosmsg_debug", "rosmsg_md5", "rosmsg_search", "rosmsgmain", "rospkg", "spec_to_str", "sys", "yaml"]

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


class RosMsgProtoException(Exception):
    """rosmsg-proto's type cannot be found."""


class RosMsgProtoArgsException(Exception):
    """rosmsg-proto's arguments are too few."""


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
    """A field_filter for get_yaml_for_msg leaving out the fields `in names`: a list's items, or,
    as rosmsg's, a string's substrings (`create_names_filter('bar')` drops `a` and `ba` too)."""
    return lambda obj: [slot for slot in obj.__slots__ if slot not in names]


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
    # False, not None, at the top: pyyaml would bracket a small message ({data: 0}); rosmsg tests
    # `flow_style_ == True`, so rosmsg-proto's `-f 1` (an int) brackets too
    text = yaml.dump(msg, Dumper=Dumper, default_flow_style=flow_style_ == 1, default_style="")
    if prefix:
        return prefix + ("\n" + prefix).join(text.splitlines())
    return text.rstrip("\n")


# ---------------------------------------------------------------- rosmsg-proto's ordered YAML


def construct_ordered_mapping(self: Any, node: Any, deep: bool = False) -> collections.OrderedDict[Any, Any]:
    """A YAML mapping as an OrderedDict (init_rosmsg_proto installs it in pyyaml)."""
    if not isinstance(node, yaml.MappingNode):
        raise yaml.constructor.ConstructorError(None, None, f"expected a mapping node, but found {node.id}",
                                                node.start_mark)
    mapping: collections.OrderedDict[Any, Any] = collections.OrderedDict()
    for key_node, value_node in node.value:
        key = self.construct_object(key_node, deep=deep)
        if not isinstance(key, collections.abc.Hashable):
            raise yaml.constructor.ConstructorError("while constructing a mapping", node.start_mark,
                                                    "found unhashable key", key_node.start_mark)
        mapping[key] = self.construct_object(value_node, deep=deep)
    return mapping


def construct_yaml_map_with_ordered_dict(self: Any, node: Any) -> Iterator[collections.OrderedDict[Any, Any]]:
    data: collections.OrderedDict[Any, Any] = collections.OrderedDict()
    yield data
    data.update(self.construct_mapping(node))


def represent_ordered_mapping(self: Any, tag: str, mapping: Any, flow_style: bool | None = None) -> yaml.MappingNode:
    """A mapping in its own order (init_rosmsg_proto installs it in pyyaml)."""
    value: list[tuple[Any, Any]] = []
    node = yaml.MappingNode(tag, value, flow_style=flow_style)
    if self.alias_key is not None:
        self.represented_objects[self.alias_key] = node
    best_style = True
    for item_key, item_value in (mapping.items() if hasattr(mapping, "items") else mapping):
        node_key = self.represent_data(item_key)
        node_value = self.represent_data(item_value)
        if not (isinstance(node_key, yaml.ScalarNode) and not node_key.style):
            best_style = False
        if not (isinstance(node_value, yaml.ScalarNode) and not node_value.style):
            best_style = False
        value.append((node_key, node_value))
    if flow_style is None:
        node.flow_style = self.default_flow_style if self.default_flow_style is not None else best_style
    return node


def init_rosmsg_proto() -> None:
    """Make pyyaml, process-wide, read mappings as OrderedDicts and write them in their order, as
    rosmsg-proto does before it writes."""
    yaml.constructor.BaseConstructor.construct_mapping = construct_ordered_mapping  # type: ignore[method-assign]
    yaml.constructor.Constructor.add_constructor("tag:yaml.org,2002:map", construct_yaml_map_with_ordered_dict)
    yaml.representer.BaseRepresenter.represent_mapping = represent_ordered_mapping  # type: ignore[method-assign]
    yaml.representer.Representer.add_representer(collections.OrderedDict,
                                                 yaml.representer.SafeRepresenter.represent_dict)


def rosmsg_cmd_prototype(args: Sequence[str]) -> str | None:
    """rosmsg-proto: the YAML of a message (`msg pkg/Type`) or a service's request (`srv ...`),
    quoted unless -H; errors are said on stderr and end the process (none with -s)."""
    init_rosmsg_proto()
    parser = OptionParser(usage="usage: rosmsgproto msg/srv [options]",
                          description="Produces output or a msg or service request, intended for tab completion "
                                      "support.")
    parser.add_option("-f", "--flow_style", dest="flow_style", type="int", default=None, action="store",
                      help="if 1 always use brackets, if 0 never use brackets. Default is a heuristic mix.")
    parser.add_option("-e", "--empty-arrays", dest="empty_arrays", default=False, action="store_true",
                      help="if true flexible size arrays are not filled with default instance")
    parser.add_option("-s", "--silent", dest="silent", default=False, action="store_true",
                      help="if true suppresses all error messages")
    parser.add_option("-p", "--prefix", metavar="prefix", default="",
                      help="prefix to print before each line, can be used for indent")
    parser.add_option("-H", "--no-hyphens", dest="no_hyphens", default="", action="store_true",
                      help="if true output has no outer hyphens")
    parser.add_option("-x", "--exclude-slots", metavar="exclude_slots", default="",
                      help="comma separated list of slot names not to print")
    options, rest = parser.parse_args(list(args))
    try:
        if len(rest) < 2:
            raise RosMsgProtoArgsException("Insufficient arguments")
        mode, message_type = "." + rest[0], rest[1]
        field_filter = None
        if options.exclude_slots is not None and options.exclude_slots.strip() != "":
            field_filter = create_names_filter(options.exclude_slots.split(","))
        if "::" in message_type:
            if not options.silent:
                parser.error("rosmsgproto does not understand C++-style namespaces (i.e. '::').\n"
                             "Please refer to msg/srv types as 'package_name/Type'.")
        elif "." in message_type and not options.silent:
            parser.error(f"invalid message type '{message_type}'.\n"
                         "Please refer to msg/srv types as 'package_name/Type'.")
        if "/" not in message_type:
            results = list(rosmsg_search(rospkg.RosPack(), mode, message_type))
            if len(results) > 1:
                raise RosMsgProtoException(f"Ambiguous message name {message_type}")
            if not results:
                raise RosMsgProtoException(f"Unknown message name {message_type}")
            message_type = results[0]
        if mode == MODE_SRV:
            srv_class = roslib.message.get_service_class(message_type)
            if srv_class is None:
                raise RosMsgProtoException(f"Unknown service class: {message_type}")
            instance = srv_class._request_class()
        elif mode == MODE_MSG:
            msg_class = roslib.message.get_message_class(message_type)
            if msg_class is None:
                raise RosMsgProtoException(f"Unknown message class: {message_type}")
            instance = msg_class()
        else:
            raise RosMsgProtoException(f"Invalid mode: {mode}")
        text = get_yaml_for_msg(instance, prefix=options.prefix, flow_style_=options.flow_style,
                                fill_arrays_=not options.empty_arrays, field_filter=field_filter)
        return text if options.no_hyphens else f'"{text}"'
    except ValueError as exc:
        if not options.silent:
            sys.stderr.write(f"Invalid type: '{exc}'")
            sys.exit(getattr(os, "EX_USAGE", 1))
    except RosMsgProtoException as exc:
        if not options.silent:
            sys.stderr.write(str(exc))
            sys.exit(1)
    except RosMsgProtoArgsException as exc:
        if not options.silent:
            sys.stderr.write(str(exc))
            sys.exit(getattr(os, "EX_USAGE", 1))
    return None


# ---------------------------------------------------------------- the command's parts


def _subdir(mode: str, what: str) -> str:
    if mode == MODE_MSG:
        return "msg"
    if mode == MODE_SRV:
        return "srv"
    raise ValueError(f"Unknown mode for {what}: {mode}")


def iterate_packages(rospack: Any, mode: str) -> Iterator[tuple[str, str]]:
    """(package, its msg or srv folder) for each package on the package path that has one."""
    subdir = _subdir(mode, "iterate_packages")
    for package in rospack.list():
        folder = os.path.join(rospack.get_path(package), subdir)
        if os.path.isdir(folder):
            yield package, folder


def rosmsg_search(rospack: Any, mode: str, base_type: str) -> Iterator[str]:
    """'pkg/<base_type>' for each package with such a message (or service)."""
    for package, folder in iterate_packages(rospack, mode):
        if os.path.isfile(os.path.join(folder, f"{base_type}{mode}")):
            yield f"{package}/{base_type}"


def rosmsg_debug(rospack: Any, mode: str, type_: str, raw: bool = False) -> None:
    """Print the type as `rosmsg show` does."""
    if mode == MODE_SRV:
        print(get_srv_text(type_, raw=raw, rospack=rospack))
    elif mode == MODE_MSG:
        print(get_msg_text(type_, raw=raw, rospack=rospack))
    else:
        raise ROSMsgException(f"Invalid mode for debug: {mode}")


def rosmsg_md5(mode: str, type_: str) -> str:
    """The type's md5sum; OSError when it cannot be loaded."""
    if mode == MODE_MSG:
        cls = roslib.message.get_message_class(type_)
    else:
        cls = roslib.message.get_service_class(type_)
    if cls is None:
        raise OSError(f"cannot load [{type_}]")
    return str(cls._md5sum)


def fullusage(mode: str) -> str:
    """The usage text of rosmsg (MODE_MSG) or rossrv (MODE_SRV)."""
    return _command.full_usage(_command.Mode(Kind.MSG if mode == MODE_MSG else Kind.SRV))


def _run_command(mode: str, run: Callable[[_command.Mode], int]) -> int:
    """A part of the command; its failures said on stderr, as the command does. Its exit status."""
    try:
        return run(_command.Mode(Kind.MSG if mode == MODE_MSG else Kind.SRV))
    except _command.CommandError as exc:
        print(exc, file=sys.stderr)
        return exc.status


def rosmsg_cmd_show(mode: str, full: str, alias: str = "show") -> int | None:
    """`rosmsg show` on sys.argv[2:]."""
    status = _run_command(mode, lambda m: _command.cmd_show(m, alias, sys.argv[2:]))
    return status or None


def rosmsg_cmd_md5(mode: str, full: str) -> None:
    """`rosmsg md5` on sys.argv[2:]."""
    _run_command(mode, lambda m: _command.cmd_md5(m, sys.argv[2:]))


def rosmsg_cmd_package(mode: str, full: str) -> None:
    """`rosmsg package` on sys.argv[2:]."""
    _run_command(mode, lambda m: _command.cmd_package(m, sys.argv[2:]))


def rosmsg_cmd_packages(mode: str, full: str, argv: Sequence[str] | None = None) -> None:
    """`rosmsg packages`: `argv` (default sys.argv[1:]) is the command and its options."""
    args = list(sys.argv[1:] if argv is None else argv)[1:]
    _run_command(mode, lambda m: _command.cmd_packages(m, args))


def rosmsg_cmd_list(mode: str, full: str, argv: Sequence[str] | None = None) -> None:
    """`rosmsg list`: `argv` (default sys.argv[1:]) is the command and its options."""
    args = list(sys.argv[1:] if argv is None else argv)[1:]
    _subdir(mode, "iterate_packages")
    _run_command(mode, lambda m: _command.cmd_list(m, args))


def rosmsgmain(mode: str = MODE_MSG) -> None:
    """The rosmsg (MODE_MSG) or rossrv (MODE_SRV) command on sys.argv; ends the process."""
    if mode not in (MODE_MSG, MODE_SRV):
        print(f"Invalid mode: {mode}", file=sys.stderr)
        sys.exit(1)
    sys.exit(_command.main_rosmsg() if mode == MODE_MSG else _command.main_rossrv())


_BUILTIN_TYPES = ("int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64", "float32", "float64",
                  "string", "bool", "char", "byte", "time", "duration")


def spec_to_str(msg_context: Any, spec: Any, buff: StringIO | None = None, indent: str = "") -> str:
    """A spec's constants and fields, each embedded message's fields below it, indented: the text
    `rosmsg show -b` prints. `msg_context` answers get_registered(type) (genmsg's MsgContext, or
    roslib.msgs); `spec` has constants, types and names (genmsg's MsgSpec, or roslib.msgs')."""
    buff = StringIO() if buff is None else buff
    for c in spec.constants:
        buff.write(f"{indent}{c.type} {c.name}={c.val_text}\n")
    for type_, name in zip(spec.types, spec.names, strict=False):
        buff.write(f"{indent}{type_} {name}\n")
        base_type = type_[:type_.find("[")] if "[" in type_ else type_
        if base_type not in _BUILTIN_TYPES:
            spec_to_str(msg_context, msg_context.get_registered(base_type), buff, indent + "  ")
    return buff.getvalue()
