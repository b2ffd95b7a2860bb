"""rosparam: set, get, load, dump, delete and list parameters on the parameter server.

Options are parsed as the real tool's optparse does (kame.cli._options; usage errors: `rosparam: error: ...`,
exit 2); `set` lets negative numbers through as values. Values follow ROS's YAML typing rules
(kame.param_yaml); a value the server cannot hold is refused before anything is set, with one
`ERROR:` line (the real tool prints a traceback). Dicts are set leaf by leaf, so they merge.
Deliberate difference: `dump -` prints to stdout (the real tool writes a file named `-`).
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from typing import Any

from kame import names, param_yaml
from kame.cli._options import OptionParser
from kame.cli._tool import Master, ToolError, ros_namespace, run, script_resolve_name
from kame.node.master_proxy import MasterError

NAME = "rosparam"
NS_KEY = "_ns"

USAGE = """rosparam is a command-line tool for getting, setting, and deleting parameters from the ROS Parameter Server.

Commands:
\trosparam set\tset parameter
\trosparam get\tget parameter
\trosparam load\tload parameters from file
\trosparam dump\tdump parameters to file
\trosparam delete\tdelete parameter
\trosparam list\tlist parameter names
"""


def _parser(usage: str) -> OptionParser:
    return OptionParser(usage=usage, prog=NAME)


def _master() -> Master:
    return Master(names.canonicalize(f"{ros_namespace()}rosparam-{os.getpid()}"))


def _resolve(name: str | None) -> str:
    return script_resolve_name(NAME, name or "")


def _get(master: Master, name: str) -> Any:
    try:
        return master.call("getParam", name)
    except MasterError as exc:
        raise ToolError(exc.message) from None


def _set_value(master: Master, name: str, value: Any, verbose: bool) -> None:
    """Set `value` at `name`, a dict key by key; everything is checked before the first call."""
    try:
        param_yaml.check(name, value)
    except param_yaml.ParamValueError as exc:
        raise ToolError(str(exc)) from None
    for key, leaf in param_yaml.leaves(name, value):
        try:
            master.call("setParam", key, leaf)
        except MasterError as exc:
            raise ToolError(exc.message) from None
        if verbose:
            print(f"set parameter [{key}] to [{leaf}]")


# ------------------------------------------------------------------ commands


def cmd_get_dump(cmd: str, argv: list[str]) -> None:
    if cmd == "dump":
        parser = _parser("usage: %prog dump [options] file [namespace]")
    else:
        parser = _parser("usage: %prog get [options] parameter")
        parser.add_argument("-p", dest="pretty", default=False, action="store_true",
                          help="pretty print. WARNING: not YAML-safe")
    parser.add_argument("-v", dest="verbose", default=False, action="store_true", help="turn on verbose output")
    options = parser.parse_args(argv)
    args = options.args
    arg: str | None = None
    ns = ""
    if not args:
        if cmd == "get":
            parser.error("invalid arguments. Please specify a parameter name")
    elif len(args) == 1:
        arg = args[0]
    elif len(args) == 2 and cmd == "dump":
        arg, ns = args
    else:
        parser.error("too many arguments")
    master = _master()
    if cmd == "get":
        name = _resolve(arg)
        if options.verbose:
            print(f"getting parameter [{name}]")
        value = _get(master, name)
        text = param_yaml.pretty_text(value) if options.pretty else param_yaml.get_text(value)
        sys.stdout.write(text)
        return
    if options.verbose:
        print(f"dumping namespace [{ns}] to file [{arg}]")
    name = _resolve(ns)
    tree = _get(master, name)
    if options.verbose:
        print("\n".join(param_yaml.verbose_lines(tree, name)))
    text = param_yaml.dump(tree)
    if not arg or arg == "-":
        sys.stdout.write(text)
        return
    try:
        with open(arg, "w") as f:
            f.write(text)
    except OSError as exc:
        raise ToolError(f"cannot write [{arg}]: {exc.strerror}") from None


def _split_negative_args(parser: OptionParser, argv: list[str]) -> tuple[argparse.Namespace, list[str]]:
    """The options parsed alone, so that `rosparam set x -3` keeps -3 as a value."""
    args: list[str] = []
    option_args: list[str] = []
    takes_value = False
    for arg in argv:
        if arg.startswith("-"):
            if arg in ("-t", "--textfile", "-b", "--binfile"):
                takes_value = True
                option_args.append(arg)
            elif takes_value:
                parser.error("-t and --textfile options require an argument")
            elif len(arg) > 1 and arg[1].isdigit():
                args.append(arg)
            else:
                option_args.append(arg)
        elif takes_value:
            takes_value = False
            option_args.append(arg)
        else:
            args.append(arg)
    options = parser.parse_args(option_args)
    return options, args


def cmd_set(argv: list[str]) -> None:
    parser = _parser("usage: %prog set [options] parameter value")
    parser.add_argument("-t", "--textfile", dest="text_file", default=None, metavar="TEXT_FILE",
                      help="set parameters to contents of text file")
    parser.add_argument("-b", "--binfile", dest="bin_file", default=None, metavar="BINARY_FILE",
                      help="set parameters to contents of binary file")
    parser.add_argument("-v", dest="verbose", default=False, action="store_true", help="turn on verbose output")
    options, args = _split_negative_args(parser, argv)
    if options.text_file and options.bin_file:
        parser.error("you may only specify one of --textfile or --binfile")
    value_text: str | None = None
    if not args:
        parser.error("invalid arguments. Please specify a parameter name")
    elif len(args) == 1:
        if not (options.text_file or options.bin_file):
            parser.error("invalid arguments. Please specify a parameter value")
    elif len(args) == 2:
        value_text = args[1]
    else:
        parser.error("too many arguments")
    name = _resolve(args[0])
    value: Any
    if options.text_file:
        if not os.path.isfile(options.text_file):
            parser.error(f"file '{options.text_file}' does not exist")
        with open(options.text_file) as f:
            value = f.read()
    elif options.bin_file:
        try:
            with open(options.bin_file, "rb") as fb:
                value = fb.read()
        except OSError as exc:
            raise ToolError(f"cannot read [{options.bin_file}]: {exc.strerror}") from None
    else:
        try:
            value = param_yaml.load(value_text or "")
        except param_yaml.ParamValueError as exc:
            raise ToolError(str(exc)) from None
    _set_value(_master(), name, value, options.verbose)


def _read_documents(filename: str, default_ns: str, verbose: bool) -> list[tuple[Any, str]]:
    if not filename or filename == "-":
        if verbose:
            print("reading parameters from stdin")
        text = sys.stdin.read()
    else:
        if not os.path.isfile(filename):
            raise ToolError(f"file [{filename}] does not exist")
        if verbose:
            print(f"reading parameters from [{filename}]")
        try:
            with open(filename, encoding="utf-8") as f:
                text = f.read()
        except UnicodeDecodeError as exc:
            raise ToolError(f"file [{filename}] is not UTF-8 text (byte {exc.start}): not a YAML file?") from None
        except OSError as exc:
            raise ToolError(f"cannot read file [{filename}]: {exc.strerror or exc}") from None
    try:
        documents = param_yaml.load_all(text)
    except param_yaml.ParamValueError as exc:
        raise ToolError(str(exc)) from None
    loaded: list[tuple[Any, str]] = []
    for doc in documents:
        ns = default_ns
        if isinstance(doc, dict) and NS_KEY in doc:
            ns = names.ns_join(default_ns, str(doc.pop(NS_KEY)))
            if verbose:
                print(f"reading parameters into namespace [{ns}]")
        loaded.append((doc, ns))
    return loaded


def cmd_load(argv: list[str]) -> None:
    parser = _parser("usage: %prog load [options] file [namespace]")
    parser.add_argument("-v", dest="verbose", default=False, action="store_true", help="turn on verbose output")
    options = parser.parse_args(argv)
    args = options.args
    if not args:
        parser.error("invalid arguments. Please specify a file name or - for stdin")
    if len(args) > 2:
        parser.error("too many arguments")
    default_ns = _resolve(args[1] if len(args) == 2 else None)
    documents = _read_documents(args[0], default_ns, options.verbose)
    for doc, ns in documents:
        if ns == "/" and not isinstance(doc, dict):
            raise ToolError("global / can only be set to a dictionary")
        try:
            param_yaml.check(ns, doc)
        except param_yaml.ParamValueError as exc:
            raise ToolError(str(exc)) from None
    master = _master()
    for doc, ns in documents:
        if options.verbose:
            print("\n".join(param_yaml.verbose_lines(doc, ns)))
        _set_value(master, ns, doc, verbose=False)


def cmd_delete(argv: list[str]) -> None:
    parser = _parser("usage: %prog delete [options] parameter")
    parser.add_argument("-v", dest="verbose", default=False, action="store_true", help="turn on verbose output")
    options = parser.parse_args(argv)
    args = options.args
    if not args:
        parser.error("invalid arguments. Please specify a parameter name")
    if len(args) > 1:
        parser.error("too many arguments")
    name = _resolve(args[0])
    master = _master()
    try:
        if name == "/":
            # The root always has a value: deleting it means emptying it.
            master.call("setParam", "/", {})
            if options.verbose:
                print("deleted ENTIRE parameter server")
        else:
            master.call("deleteParam", name)
            if options.verbose:
                print(f"deleted parameter [{name}]")
    except MasterError as exc:
        raise ToolError(exc.message) from None


def cmd_list(argv: list[str]) -> None:
    parser = _parser("usage: %prog list [namespace]")
    parsed = parser.parse_args(argv)
    args = parsed.args
    ns = "/"
    if len(args) == 1:
        ns = _resolve(args[0])
    elif len(args) > 1:
        parser.error("too many arguments")
    prefix = names.make_global_ns(ns)
    params = sorted(str(n) for n in _master().call("getParamNames"))
    print("\n".join(n for n in params if n.startswith(prefix)))


def _main(argv: list[str]) -> int:
    if not argv:
        sys.stdout.write(USAGE + "\n")
        return 0
    command, rest = argv[0], argv[1:]
    if command in ("get", "dump"):
        cmd_get_dump(command, rest)
    elif command == "set":
        cmd_set(rest)
    elif command == "load":
        cmd_load(rest)
    elif command == "delete":
        cmd_delete(rest)
    elif command == "list":
        cmd_list(rest)
    else:
        sys.stdout.write(USAGE + "\n")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    return run(_main, argv)


if __name__ == "__main__":
    sys.exit(main())
