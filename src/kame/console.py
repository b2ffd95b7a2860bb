"""roscpp's console line (rosconsole's default format), as kame's ports of C++ programs print it:
`[ INFO] [1795311549.578038800]: text`, the severity padded to five, the time in nanoseconds,
and the whole line wrapped in the severity's colour (INFO's is the reset code), to a terminal
or not, unless NO_COLOR is set."""

from __future__ import annotations

from collections.abc import Mapping

RESET = "\033[0m"
ROSCPP_COLOURS = {"DEBUG": "\033[32m", "INFO": RESET, "WARN": "\033[33m", "ERROR": "\033[31m", "FATAL": "\033[31m"}


def roscpp_colour(environ: Mapping[str, str]) -> bool:
    """Whether roscpp colours its lines: always, unless NO_COLOR is set (to anything)."""
    return "NO_COLOR" not in environ


def roscpp_stamp(ns: int) -> str:
    """A time in nanoseconds as rosconsole's ${time}: seconds, a dot, nine digits."""
    return f"{ns // 1_000_000_000}.{ns % 1_000_000_000:09d}"


def coloured(severity: str, line: str, colour: bool) -> str:
    """`line` wrapped in `severity`'s colour, as rosconsole writes it (unchanged without colour)."""
    return f"{ROSCPP_COLOURS[severity]}{line}{RESET}" if colour else line


def roscpp_line(severity: str, text: str, stamp_ns: int, colour: bool) -> str:
    """One console line in rosconsole's default format (no newline)."""
    return coloured(severity, f"[{severity:>5}] [{roscpp_stamp(stamp_ns)}]: {text}", colour)
