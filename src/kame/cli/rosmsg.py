"""rosmsg and rossrv: show, list, md5, package and packages of message and service types.

Command-line parsing and printing only; the texts come from kame.msg.describe. Options are
parsed as the real tools' optparse does (kame.cli._options), so usage, help and errors match
(usage errors: usage line and `rosmsg: error: ...` on stderr, exit 2). Lookup failures print
one line on stderr and exit 1, except an unknown package or a malformed type name given to
`package`/`md5`, which exit 64 (EX_USAGE) as in real ROS. Deliberate differences: a failed
`md5` exits 1 (real rosmsg exits 0), an unknown package is reported on one line (rospkg adds
its `ROS path [i]=` lines), and an empty stdin is a usage error (real rosmsg spins forever).
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from kame.cli._options import OptionParser
from kame.msg.catalog import MsgCatalog
from kame.msg.describe import (
    Kind,
    all_types,
    describe_msg,
    describe_srv,
    find_by_short_name,
    load_msg,
    load_srv,
    packages_with,
    types_in_package,
)
from kame.msg.errors import MessageError

EX_USAGE = 64


class CommandError(Exception):
    """A failure to report as one line on stderr, with an exit status."""

    def __init__(self, message: str, status: int = 1) -> None:
        super().__init__(message)
        self.status = status


@dataclass(frozen=True)
class Mode:
    kind: Kind

    @property
    def cmd(self) -> str:
        return "ros" + self.kind.value

    @property
    def ext(self) -> str:
        return "." + self.kind.value

    @property
    def full(self) -> str:
        return "message type" if self.kind is Kind.MSG else "service type"

    @property
    def noun(self) -> str:
        return "message" if self.kind is Kind.MSG else "service"


def full_usage(mode: Mode) -> str:
    cmd, noun = mode.cmd, mode.noun
    return (
        f"{cmd} is a command-line tool for displaying information about ROS {noun.capitalize()} types.\n"
        "\n"
        "Commands:\n"
        f"\t{cmd} show\tShow {noun} description\n"
        f"\t{cmd} info\tAlias for {cmd} show\n"
        f"\t{cmd} list\tList all {noun}s\n"
        f"\t{cmd} md5\tDisplay {noun} md5sum\n"
        f"\t{cmd} package\tList {noun}s in a package\n"
        f"\t{cmd} packages\tList packages that contain {noun}s\n"
        "\n"
        f"Type {cmd} <command> -h for more detailed usage\n"
    )


def _out(text: str) -> None:
    sys.stdout.write(text)
    sys.stdout.flush()


def _parser(mode: Mode, usage: str) -> OptionParser:
    return OptionParser(usage=usage, prog=mode.cmd)


def _one_argument(
    parser: OptionParser, mode: Mode, args: Sequence[str]
) -> tuple[argparse.Namespace, str]:
    """The single type/package argument, read from stdin (first non-blank line) when absent."""
    options = parser.parse_args(list(args))
    rest = options.args
    if len(rest) > 1:
        parser.error(f"you may only specify one {mode.full}")
    if rest:
        return options, rest[0]
    while True:
        line = sys.stdin.readline()
        if not line:
            parser.error(f"no {mode.full} given and none on standard input")
        if line.strip():
            return options, line.strip()


def _expanded(catalog: MsgCatalog, mode: Mode, type_name: str, raw: bool) -> str:
    try:
        if mode.kind is Kind.MSG:
            msg = load_msg(catalog, type_name)
            return msg.text if raw else describe_msg(catalog, msg)
        srv = load_srv(catalog, type_name)
        return srv.text if raw else describe_srv(catalog, srv)
    except MessageError as exc:
        what = "Unable to load msg" if mode.kind is Kind.MSG else "Unknown srv type"
        raise CommandError(f"{what} [{type_name}]: {exc}") from exc


def cmd_show(mode: Mode, alias: str, args: Sequence[str]) -> int:
    parser = _parser(mode, f"usage: {mode.cmd} {alias} [options] <{mode.full}>")
    parser.add_argument(
        "-r", "--raw", dest="raw", default=False, action="store_true",
        help="show raw message text, including comments",
    )
    parser.add_argument(
        "-b", "--bag", dest="bag", default=None, help="show message from .bag file", metavar="BAGFILE"
    )
    options, arg = _one_argument(parser, mode, args)
    if arg.endswith(mode.ext):
        arg = arg[: -len(mode.ext)]
    if "::" in arg:
        parser.error(
            f"{mode.cmd} does not understand C++-style namespaces (i.e. '::').\n"
            "Please refer to msg/srv types as 'package_name/Type'."
        )
    elif "." in arg:
        parser.error(f"invalid message type '{arg}'.\nPlease refer to msg/srv types as 'package_name/Type'.")
    if options.bag:
        if not os.path.exists(options.bag):
            raise CommandError(f"ERROR: bag file [{options.bag}] does not exist")
        raise CommandError("ERROR: reading types from a bag file is not supported by kame yet")
    catalog = MsgCatalog.from_environment()
    raw = bool(options.raw)
    if "/" in arg:
        _out(_expanded(catalog, mode, arg, raw) + "\n")
        return 0
    found = find_by_short_name(catalog, arg, mode.kind)
    if not found:
        raise CommandError(f"Could not find msg '{arg}'")
    for type_name in found:
        _out(f"[{type_name}]:\n")
        _out(_expanded(catalog, mode, type_name, raw) + "\n")
    return 0


def _md5(catalog: MsgCatalog, mode: Mode, type_name: str) -> str:
    try:
        if mode.kind is Kind.MSG:
            load_msg(catalog, type_name)
            return catalog.md5sum(type_name)
        load_srv(catalog, type_name)
        return catalog.srv_md5sum(type_name)
    except MessageError as exc:
        raise CommandError(f"Cannot locate [{type_name}]") from exc


def cmd_md5(mode: Mode, args: Sequence[str]) -> int:
    parser = _parser(mode, f"usage: {mode.cmd} md5 <{mode.full}>")
    _, arg = _one_argument(parser, mode, args)
    catalog = MsgCatalog.from_environment()
    if "/" in arg:
        if arg == "/Header" and mode.kind is Kind.MSG:
            arg = "std_msgs/Header"  # as roslib resolves it
        elif arg.startswith("/"):
            raise CommandError(f"Invalid type: 'message type is missing package name: {arg}'", EX_USAGE)
        if arg.count("/") > 1:
            raise CommandError(f"Invalid type: 'invalid name [{arg}]'", EX_USAGE)
        _out(_md5(catalog, mode, arg) + "\n")
        return 0
    matches = find_by_short_name(catalog, arg, mode.kind)
    if not matches:
        raise CommandError(f"No messages matching the name [{arg}]")
    for type_name in matches:
        _out(f"[{type_name}]: {_md5(catalog, mode, type_name)}\n")
    return 0


def cmd_package(mode: Mode, args: Sequence[str]) -> int:
    parser = _parser(mode, f"usage: {mode.cmd} package <package>")
    parser.add_argument(
        "-s", dest="single_line", default=False, action="store_true",
        help="list all msgs on a single line",  # sic: rossrv says msgs too
    )
    options, package = _one_argument(parser, mode, args)
    catalog = MsgCatalog.from_environment()
    if package not in catalog.packages:
        raise CommandError(f"Invalid package: {package}", EX_USAGE)
    types = types_in_package(catalog, package, mode.kind)
    _out((" " if options.single_line else "\n").join(types) + "\n")
    return 0


def cmd_packages(mode: Mode, args: Sequence[str]) -> int:
    parser = _parser(mode, f"usage: {mode.cmd} packages")
    parser.add_argument(
        "-s", dest="single_line", default=False, action="store_true",
        help="list all packages on a single line",
    )
    options = parser.parse_args(list(args))
    catalog = MsgCatalog.from_environment()
    _out((" " if options.single_line else "\n").join(packages_with(catalog, mode.kind)) + "\n")
    return 0


def cmd_list(mode: Mode, args: Sequence[str]) -> int:
    parser = _parser(mode, f"usage: {mode.cmd} list")
    parser.parse_args(list(args))
    catalog = MsgCatalog.from_environment()
    _out("".join(f"{t}\n" for t in all_types(catalog, mode.kind)))
    return 0


def _run(mode: Mode, argv: Sequence[str]) -> int:
    if not argv:
        _out(full_usage(mode) + "\n")
        return 0
    command, args = argv[0], argv[1:]
    commands: dict[str, Callable[[], int]] = {
        "show": lambda: cmd_show(mode, "show", args),
        "info": lambda: cmd_show(mode, "info", args),
        "md5": lambda: cmd_md5(mode, args),
        "package": lambda: cmd_package(mode, args),
        "packages": lambda: cmd_packages(mode, args),
        "list": lambda: cmd_list(mode, args),
    }
    if command == "--help":
        _out(full_usage(mode) + "\n")
        return 0
    handler = commands.get(command)
    if handler is None:
        _out(full_usage(mode) + "\n")
        return EX_USAGE
    return handler()


def _main(kind: Kind, argv: Sequence[str] | None) -> int:
    mode = Mode(kind)
    try:
        return _run(mode, sys.argv[1:] if argv is None else argv)
    except CommandError as exc:
        sys.stderr.write(f"{exc}\n")
        return exc.status
    except MessageError as exc:
        sys.stderr.write(f"{exc}\n")
        return 1
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        # The reader went away (`rosmsg list | head`): drop what is left, no traceback at exit.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0


def main_rosmsg(argv: Sequence[str] | None = None) -> int:
    """Entry point of the `rosmsg` console script."""
    return _main(Kind.MSG, argv)


def main_rossrv(argv: Sequence[str] | None = None) -> int:
    """Entry point of the `rossrv` console script."""
    return _main(Kind.SRV, argv)


if __name__ == "__main__":
    sys.exit(main_rosmsg())
