"""dynparam: list, get, set, set_from_parameters, load and dump a dynamically reconfigurable node's configuration.

Run as `rosrun dynamic_reconfigure dynparam <command> ...`, with the real tool's commands,
options (-t/--timeout) and messages. Deliberate difference: dump writes plain YAML maps (the
real tool writes its Config class's Python tags, which only its own Python can load back).
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from typing import Any

import yaml

from kame import param_yaml
from kame.cli._options import OptionParser
from kame.client import core, process
from kame.client.errors import ROSException, ROSInterruptException
from kame.reconfigure.client import Client
from kame.reconfigure.errors import DynamicReconfigureParameterException

NAME = "dynparam"
USAGE = """dynparam is a command-line tool for getting, setting, and
deleting parameters of a dynamically configurable node.

Commands:
\tdynparam set                  configure node
\tdynparam set_from_parameters  copy configuration from parameter server
\tdynparam get                  get node configuration
\tdynparam load                 load configuration from file
\tdynparam dump                 dump configuration to file
\tdynparam list                 list configurable nodes

Type dynparam <command> -h for more detailed usage, e.g. 'dynparam get -h'
"""
SET_USAGE = """%prog set [options] node parameter value
   or: %prog set [options] node values

Examples:
  dynparam set wge100_camera camera_url foo
  dynparam set wge100_camera "{'camera_url':'foo', 'brightness':58}" """
EXAMPLE_NODE = ('<node name="$(anon adjust-wge100_camera)" pkg="dynamic_reconfigure" type="dynparam" '
                'args="set_from_parameters wge100_camera">')
SET_FROM_PARAMETERS_USAGE = f"""%prog set_from_parameters [options] node

Example command line:
  dynparam set_from_parameters wge100_camera _camera_url:=foo

Example launch file:
  <launch>
    {EXAMPLE_NODE}
      <param name="camera_url" value="foo" />
      <param name="brightness" value="58" />
    </node>
  </launch>"""
BAD_SET = ("invalid arguments. Please specify either a node name, parameter name and parameter value, "
           "or a node name and a YAML dictionary")


def _parser(usage: str) -> OptionParser:
    parser = OptionParser(usage=usage if usage.startswith("%prog") else "%prog " + usage, prog=NAME)
    parser.add_argument("-t", "--timeout", type=float, default=None, help="timeout in secs")
    return parser


def _connect(argv: Sequence[str]) -> None:
    process.init_node("dynparam", argv=list(argv), anonymous=True)


def _node_and_more(parser: OptionParser, args: Sequence[str], more: str | None) -> tuple[Any, list[str]]:
    options = parser.parse_args(list(args))
    rest: list[str] = options.args
    if not rest:
        parser.error("invalid arguments. Please specify a node name")
    wanted = 1 if more is None else 2
    if len(rest) < wanted:
        parser.error(f"invalid arguments. Please specify an {more}")
    if len(rest) > wanted:
        parser.error("too many arguments")
    return options, rest


def set_params(node: str, params: dict[str, Any], timeout: float | None) -> None:
    client = Client(node, timeout=timeout)
    try:
        client.update_configuration(params)
    except DynamicReconfigureParameterException as exc:
        print("error updating parameters: " + str(exc))
    finally:
        client.close()


def get_params(node: str, timeout: float | None) -> Any:
    client = Client(node, timeout=timeout)
    try:
        return client.get_configuration(timeout=timeout)
    finally:
        client.close()


def plain(value: Any) -> Any:
    """A configuration as plain dicts, for YAML."""
    if isinstance(value, dict):
        return {key: plain(item) for key, item in value.items()}
    return value


def do_list(argv: Sequence[str]) -> None:
    _connect(argv)
    services = process.get_master().call("getSystemState")[2]
    suffix = "/set_parameters"
    for name in sorted(service[:-len(suffix)] for service, _ in services if service.endswith(suffix)):
        print(name)


def do_set(argv: Sequence[str], args: Sequence[str]) -> None:
    # values may be negative numbers: only a dash before a non-digit starts an option
    words = [a for a in args if not a.startswith("-") or (len(a) > 1 and a[1].isdigit())]
    option_words = [a for a in args if a not in words]
    parser = _parser(SET_USAGE)
    options = parser.parse_args(option_words)
    if len(words) > 3:
        parser.error("too many arguments")
    if len(words) < 2:
        parser.error(BAD_SET)
    if len(words) == 2:
        values = param_yaml.load(words[1])
        if not isinstance(values, dict):
            parser.error(BAD_SET)
    else:
        values = {words[1]: words[2]}
    _connect(argv)
    try:
        set_params(words[0], values, options.timeout)
    except ROSException:
        print(f"couldn't set parameters at node {words[0]}")


def do_get(argv: Sequence[str], args: Sequence[str]) -> None:
    options, rest = _node_and_more(_parser("get [options] node"), args, None)
    _connect(argv)
    params = get_params(rest[0], options.timeout)
    if params is not None:
        print(params)


def do_set_from_parameters(argv: Sequence[str], args: Sequence[str]) -> None:
    options, rest = _node_and_more(_parser(SET_FROM_PARAMETERS_USAGE), args, None)
    _connect(argv)
    try:
        params = process.get_param("~")
    except KeyError:
        print("error updating parameters: no parameters found on parameter server", file=sys.stderr)
        return
    set_params(rest[0], params, options.timeout)


def do_load(argv: Sequence[str], args: Sequence[str]) -> None:
    options, rest = _node_and_more(_parser("load [options] node file"), args, "input file")
    with open(rest[1], encoding="utf-8") as source:
        params: dict[str, Any] = {}
        for document in param_yaml.load_all(source.read()):
            params.update(document)
    _connect(argv)
    set_params(rest[0], params, options.timeout)


def do_dump(argv: Sequence[str], args: Sequence[str]) -> None:
    options, rest = _node_and_more(_parser("dump [options] node file"), args, "output file")
    _connect(argv)
    params = get_params(rest[0], options.timeout)
    if params is None:
        print(f"couldn't get parameters from node {rest[0]}")
        return
    with open(rest[1], "w", encoding="utf-8") as target:
        yaml.safe_dump(plain(params), target, default_flow_style=False)


def main(argv: Sequence[str] | None = None) -> int:
    full = list(sys.argv if argv is None else argv)
    args = process.myargv(full)
    if len(args) < 2 or args[1] not in ("list", "set", "get", "set_from_parameters", "load", "dump"):
        print(USAGE)
        return 1
    command, rest = args[1], args[2:]
    try:
        if command == "list":
            do_list(full)
        elif command == "set":
            do_set(full, rest)
        elif command == "get":
            do_get(full, rest)
        elif command == "set_from_parameters":
            do_set_from_parameters(full, rest)
        elif command == "load":
            do_load(full, rest)
        else:
            do_dump(full, rest)
    except ROSInterruptException:
        pass
    finally:
        core.signal_shutdown("dynparam done")
    return 0


if __name__ == "__main__":
    sys.exit(main())
