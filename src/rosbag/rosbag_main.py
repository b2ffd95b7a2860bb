"""rosbag.rosbag_main: the rosbag command's entry point and subcommands, over kame.cli.rosbag.

Each `*_cmd(argv)` takes the arguments after the subcommand, prints what `rosbag <cmd>` prints
and ends the process with the command's status when it fails, as rosbag's do.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Sequence

from kame.cli import rosbag as _command
from rosbag.bag import (
    Bag,
    Compression,
    ROSBagEncryptException,
    ROSBagEncryptNotSupportedException,
    ROSBagException,
    ROSBagFormatException,
    ROSBagUnindexedException,
)

__all__ = ["Bag", "Compression", "ROSBagEncryptException", "ROSBagEncryptNotSupportedException", "ROSBagException",
           "ROSBagFormatException", "ROSBagUnindexedException", "check_cmd", "compress_cmd", "decompress_cmd",
           "filter_cmd", "fix_cmd", "info_cmd", "play_cmd", "record_cmd", "reindex_cmd", "rosbagmain"]


def _ending_on_failure(command: Callable[[list[str]], int]) -> Callable[[Sequence[str]], None]:
    def run(argv: Sequence[str]) -> None:
        status = command(list(argv))
        if status:
            sys.exit(status)

    run.__doc__ = f"`rosbag {command.__name__[4:]}` on `argv` (the arguments after the subcommand)."
    return run


record_cmd = _ending_on_failure(_command.cmd_record)
info_cmd = _ending_on_failure(_command.cmd_info)
play_cmd = _ending_on_failure(_command.cmd_play)
check_cmd = _ending_on_failure(_command.cmd_check)
fix_cmd = _ending_on_failure(_command.cmd_fix)
filter_cmd = _ending_on_failure(_command.cmd_filter)
compress_cmd = _ending_on_failure(_command.cmd_compress)
decompress_cmd = _ending_on_failure(_command.cmd_decompress)
reindex_cmd = _ending_on_failure(_command.cmd_reindex)


def rosbagmain(argv: Sequence[str] | None = None) -> None:
    """The rosbag command on `argv` (sys.argv: the program, then the subcommand); ends the process."""
    sys.exit(_command.main(None if argv is None else list(argv)[1:]))
