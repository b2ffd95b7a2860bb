"""rospy.rosconsole: the `rosconsole` command (list, get and set a node's logger levels; echo
/rosout), as rospy ships it: `main(argv)`."""

from __future__ import annotations, print_function  # print_function: a name rospy's module has

import os
import re
import sys
from argparse import ArgumentParser
from datetime import datetime, tzinfo
from typing import Any, NoReturn

import rospy
from kame.client.errors import ROSException
from rosgraph_msgs.msg import Log
from rospy.logger_level_service_caller import LoggerLevelServiceCaller, ROSConsoleException

__all__ = [
    "NAME",
    "ArgumentParser",
    "Log",
    "LoggerLevelServiceCaller",
    "ROSConsoleException",
    "RosConsoleEcho",
    "datetime",
    "error",
    "main",
    "print_function",
    "tzlocal",
]

NAME = "rosconsole"


def tzlocal() -> tzinfo | None:
    """This machine's time zone (dateutil's tzlocal() in rospy)."""
    return datetime.now().astimezone().tzinfo


def error(status: int, msg: str) -> NoReturn:
    print(f"{NAME}: error: {msg}", file=sys.stderr)
    sys.exit(status)


def _option_parser(usage: str) -> Any:
    from optparse import OptionParser

    return OptionParser(usage=usage, prog=NAME)


def _rosconsole_cmd_list(argv: list[str]) -> None:
    parser = _option_parser("usage: %prog list <node>")
    _options, args = parser.parse_args(argv[2:])
    if not args:
        parser.error("you must specify a node to list loggers")
    elif len(args) > 1:
        parser.error("you may only specify one node to list")
    print("\n".join(LoggerLevelServiceCaller().get_loggers(args[0])))


def _rosconsole_cmd_set(argv: list[str]) -> None:
    levels = ", ".join(LoggerLevelServiceCaller().get_levels())
    parser = _option_parser(f"usage: %prog set <node> <logger> <level>\n\n <level> must be one of [{levels}]")
    _options, args = parser.parse_args(argv[2:])
    if len(args) < 3:
        parser.error("you must specify a node, a logger and a level")
    logger_level = LoggerLevelServiceCaller()
    logger_level.get_loggers(args[0])
    if args[1] not in logger_level._current_levels:
        error(2, "node " + args[0] + " does not contain logger " + args[1])
    if args[2].lower() not in logger_level.get_levels():
        parser.error("invalid level")
    logger_level.send_logger_change_message(args[0], args[1], args[2])


def _rosconsole_cmd_get(argv: list[str]) -> None:
    parser = _option_parser("usage: %prog get <node> <logger>")
    _options, args = parser.parse_args(argv[2:])
    if len(args) < 2:
        parser.error("you must specify a node and a logger")
    logger_level = LoggerLevelServiceCaller()
    logger_level.get_loggers(args[0])
    if args[1] not in logger_level._current_levels:
        error(2, "node " + args[0] + " does not contain logger " + args[1])
    print(logger_level._current_levels[args[1]])


class RosConsoleEcho:
    """Prints the /rosout (or `options.topic`) lines at or above `options.level` whose node
    name matches `options.filter`."""

    LEVEL_COLOR = {"DEBUG": 92, "INFO": 97, "WARN": 93, "ERROR": 91, "FATAL": 95}
    LEVEL_MAX_LENGTH = max(len(level) for level in LEVEL_COLOR)

    def __init__(self, options: Any) -> None:
        self._filter = re.compile(options.filter)
        self._level = getattr(Log, options.level.upper())
        self._nocolor = options.nocolor
        self._verbose = options.verbose
        self._level_string_map = {getattr(Log, level): self._stringify(level) for level in self.LEVEL_COLOR}
        callback = self._once_callback if options.once else self._callback
        rospy.Subscriber(options.topic, Log, callback)

    def _stringify(self, level: str) -> str:
        string = level.ljust(RosConsoleEcho.LEVEL_MAX_LENGTH)
        return string if self._nocolor else f"\033[{self.LEVEL_COLOR[level]}m{string}\033[0m"

    @staticmethod
    def get_levels() -> list[str]:
        return sorted(RosConsoleEcho.LEVEL_COLOR, key=lambda level: getattr(Log, level))

    def _print(self, msg: Any) -> None:
        print(f"[ {self._level_string_map[msg.level]} ] [\033[1m{msg.name}\033[21m]: {msg.msg}")
        if self._verbose:
            stamp_sec = msg.header.stamp.to_sec()
            stamp_tz = datetime.fromtimestamp(stamp_sec, tzlocal())
            print(f"          [{stamp_tz} ({stamp_sec:.6f})] [{msg.function}]: {msg.file}:{msg.line}")

    def _callback(self, msg: Any) -> None:
        if self._filter.search(msg.name) and msg.level >= self._level:
            self._print(msg)

    def _once_callback(self, msg: Any) -> None:
        self._callback(msg)
        rospy.signal_shutdown("Done")


def _get_cmd_echo_argparse(prog: str) -> ArgumentParser:
    parser = ArgumentParser(prog=prog, description="Print logger messages")
    parser.add_argument("filter", metavar="FILTER", type=str, nargs="?", default=".*",
                        help="regular expression to filter the logger name (default: %(default)s)")
    parser.add_argument("-l", "--level", action="store", metavar="LEVEL", type=str, default="warn", dest="level",
                        choices=[level.lower() for level in RosConsoleEcho.get_levels()],
                        help="minimum logger level to print (default: %(default)s)")
    parser.add_argument("-1", "--once", action="store_true", dest="once", help="prints one logger message and exits")
    parser.add_argument("--topic", action="store", metavar="TOPIC", type=str, default="/rosout", dest="topic",
                        help="topic to read the logger messages from (default: %(default)s)")
    parser.add_argument("--nocolor", action="store_true", help="output without color")
    parser.add_argument("-v", "--verbose", action="store_true", help="print full logger details")
    return parser


def _rosconsole_cmd_echo(argv: list[str]) -> None:
    parser = _get_cmd_echo_argparse(" ".join([os.path.basename(argv[0]), argv[1]]))
    args = parser.parse_args(argv[2:])
    rospy.init_node("rosconsole", anonymous=True)
    RosConsoleEcho(args)
    rospy.spin()


def _fullusage() -> NoReturn:
    print("""rosconsole is a command-line tool for configuring the logger level of ROS nodes.

Commands:
\trosconsole get\tdisplay level for a logger
\trosconsole list\tlist loggers for a node
\trosconsole set\tset level for a logger
\trosconsole echo\tprint logger messages

Type rosconsole <command> -h for more detailed usage, e.g. 'rosconsole list -h'
""")
    sys.exit(getattr(os, "EX_USAGE", 1))


def main(argv: list[str] | None = None) -> None:
    from rosgraph import MasterException

    if argv is None:
        argv = sys.argv
    rospy.init_node("rosconsole", anonymous=True)
    argv = rospy.myargv(argv)
    if len(argv) == 1:
        _fullusage()
    commands = {"get": _rosconsole_cmd_get, "list": _rosconsole_cmd_list, "set": _rosconsole_cmd_set,
                "echo": _rosconsole_cmd_echo}
    try:
        command = commands.get(argv[1])
        if command is None:
            _fullusage()
        command(argv)
    except OSError as exc:
        error(1, f"Network communication failed; most likely failed to communicate with master: {exc}")
    except (ROSConsoleException, ROSException, MasterException) as exc:
        error(1, str(exc))
    except KeyboardInterrupt:
        pass
