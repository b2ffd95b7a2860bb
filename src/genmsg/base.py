"""genmsg.base: the file layout's names, the definition language's delimiters, the two errors
and genmsg's verbose log (to stderr, off unless log_verbose(True))."""

from __future__ import annotations

import inspect
import pprint
import sys
from typing import Any

__all__ = ["COMMENTCHAR", "CONSTCHAR", "EXT_MSG", "EXT_SRV", "IODELIM", "MSG_DIR", "SEP", "SRV_DIR", "InvalidMsgSpec",
           "MsgGenerationException", "log", "log_verbose", "plog", "verbose"]

SEP = "/"
MSG_DIR = "msg"
SRV_DIR = "srv"
EXT_MSG = ".msg"
EXT_SRV = ".srv"
CONSTCHAR = "="
COMMENTCHAR = "#"
IODELIM = "---"

verbose = False


def log_verbose(value: bool) -> None:
    global verbose
    verbose = value


def _caller() -> str:
    frame = inspect.stack()[2]
    return f"{frame.filename}:{frame.lineno}"


def log(*args: Any) -> None:
    if verbose:
        print(_caller(), file=sys.stderr)
        print(" ".join(str(x) for x in args), file=sys.stderr)


def plog(msg: str, obj: Any) -> None:
    if verbose:
        print(_caller(), file=sys.stderr)
        print(msg, " ", file=sys.stderr)
        pprint.pprint(obj, stream=sys.stderr)


class InvalidMsgSpec(Exception):
    """A message or service definition that cannot be parsed."""


class MsgGenerationException(Exception):
    """A file that cannot be generated."""
