"""argparse for the ros* commands whose usage, help and errors users know from optparse.

ros_comm wrote most of its tools with optparse: `Usage: rostopic echo [options] /topic`,
an `Options:` list with `--bag=BAGFILE`, and errors as `rostopic: error: no such option: -x`
after the usage line, exit 2. kame parses every command line with argparse; OptionParser is
an argparse parser that prints those texts as optparse does, so both the tools written with
argparse in ROS (rostopic type, delay) and those written with optparse keep their output:
- the arguments that are not options are collected, in order and between options, in `args`
  (optparse's leftover list); `--` ends the options;
- help is optparse's IndentedHelpFormatter layout (help column at most 24, COLUMNS wide);
  an option that takes the words after it (nargs="*", what optparse tools did with a
  callback) is listed by its name alone, as optparse listed those;
- argparse's own error texts are given in optparse's words (no such option, option requires
  1 argument, invalid integer value, ...).
"""

from __future__ import annotations

import argparse
import os
import re
import sys
import textwrap
from collections.abc import Sequence
from typing import Any, NoReturn

_MAX_HELP_POSITION = 24
_TYPE_NAMES = {"int": "integer", "float": "floating-point"}


class OptionParser(argparse.ArgumentParser):
    def __init__(self, usage: str = "%prog [options]", prog: str | None = None, description: str | None = None,
                 epilog: str | None = None) -> None:
        if usage.lower().startswith("usage: "):  # optparse drops it: it prints its own "Usage: "
            usage = usage[len("usage: "):]
        super().__init__(prog=prog or os.path.basename(sys.argv[0]), usage=usage, description=description,
                         epilog=epilog)
        self.add_argument("args", nargs="*", help=argparse.SUPPRESS)
        self._argv: list[str] = []

    def parse_args(self, args: Sequence[str] | None = None, namespace: Any = None) -> Any:  # type: ignore[override]
        self._argv = list(sys.argv[1:] if args is None else args)
        return self.parse_intermixed_args(self._argv, namespace)

    # ---------------------------------------------------------------- texts

    def format_usage(self) -> str:
        return f"Usage: {(self.usage or '').replace('%prog', self.prog)}\n"

    def format_help(self) -> str:
        width = _width()
        parts = [self.format_usage() + "\n"]
        if self.description:
            parts.append(textwrap.fill(self.description, width) + "\n\n")
        parts.append(self._format_options(width))
        if self.epilog:
            parts.append("\n" + textwrap.fill(self.epilog, width) + "\n")
        return "".join(parts)

    def _format_options(self, width: int) -> str:
        options = [(self._invocation(a), a) for a in self._actions if a.option_strings]
        if not options:
            return ""
        # optparse measures the hidden options too
        help_position = min(max(len(text) + 2 for text, _ in options) + 2, _MAX_HELP_POSITION)
        shown = [(text, a) for text, a in options if a.help != argparse.SUPPRESS]
        help_width = max(width - help_position, 11)
        lines = ["Options:\n"]
        for text, action in shown:
            columns = help_position - 4
            if len(text) > columns:
                lines.append(f"  {text}\n")
                first_indent = help_position
            else:
                lines.append(f"  {text:<{columns}}  ")
                first_indent = 0
            if action.help:
                wrapped = textwrap.wrap(action.help, help_width)
                lines.append(" " * first_indent + wrapped[0] + "\n")
                lines.extend(" " * help_position + line + "\n" for line in wrapped[1:])
            elif not lines[-1].endswith("\n"):
                lines.append("\n")
        return "".join(lines)

    @staticmethod
    def _invocation(action: argparse.Action) -> str:
        shorts = [s for s in action.option_strings if not s.startswith("--")]
        longs = [s for s in action.option_strings if s.startswith("--")]
        if action.nargs in (0, "*"):
            return ", ".join(shorts + longs)
        metavar = action.metavar or (action.dest or "").upper()
        return ", ".join([f"{s} {metavar}" for s in shorts] + [f"{s}={metavar}" for s in longs])

    # ---------------------------------------------------------------- errors

    def error(self, message: str) -> NoReturn:
        self.print_usage(sys.stderr)
        sys.stderr.write("\n")
        self.exit(2, f"{self.prog}: error: {self._optparse_words(message)}\n")

    def _typed(self, option_strings: str) -> str:
        """Which of an option's names (argparse joins them with '/') the user typed."""
        names = option_strings.split("/")
        for arg in reversed(self._argv):
            for name in names:
                if arg == name or arg.startswith(name + "=") or (not name.startswith("--") and arg.startswith(name)):
                    return name
        return names[0]

    def _optparse_words(self, message: str) -> str:
        match = re.fullmatch(r"unrecognized arguments: (\S+).*", message, re.S)
        if match:
            return f"no such option: {match.group(1).split('=')[0]}"
        match = re.fullmatch(r"argument (\S+): expected one argument", message)
        if match:
            return f"{self._typed(match.group(1))} option requires 1 argument"
        match = re.fullmatch(r"argument (\S+): invalid (\w+) value: (.*)", message)
        if match:
            kind = _TYPE_NAMES.get(match.group(2), match.group(2))
            return f"option {self._typed(match.group(1))}: invalid {kind} value: {match.group(3)}"
        match = re.fullmatch(r"argument (\S+): ignored explicit argument .*", message)
        if match:
            return f"{self._typed(match.group(1))} option does not take a value"
        match = re.fullmatch(r"ambiguous option: (\S+) could match (.*)", message)
        if match:
            return f"ambiguous option: {match.group(1).split('=')[0]} ({match.group(2)}?)"
        return message


def _width() -> int:
    try:
        return int(os.environ["COLUMNS"]) - 2
    except (KeyError, ValueError):
        return 78
