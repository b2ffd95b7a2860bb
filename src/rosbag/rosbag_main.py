"""rosbag.rosbag_main: the rosbag command's entry point and subcommands, over kame.cli.rosbag,
and the parts of it scripts reuse (bag_op and its ops, ProgressMeter, RosbagCmds, the option
callbacks).

Each `*_cmd(argv)` takes the arguments after the subcommand, prints what `rosbag <cmd>` prints
and ends the process with the command's status when it fails, as rosbag's do.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import sys
import time
from collections import UserDict
from collections.abc import Callable, Sequence
from typing import Any

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

__all__ = ["Bag", "Compression", "ProgressMeter", "ROSBagEncryptException", "ROSBagEncryptNotSupportedException",
           "ROSBagException", "ROSBagFormatException", "ROSBagUnindexedException", "RosbagCmds", "UserDict", "bag_op",
           "change_compression_op", "check_cmd", "compress_cmd", "decompress_cmd", "filter_cmd", "fix_cmd",
           "handle_pause_topics", "handle_split", "handle_topics", "info_cmd", "play_cmd", "print_trans", "record_cmd",
           "reindex_cmd", "reindex_op", "rosbagmain"]


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


# ---------------------------------------------------------------- what rosbag's scripts reuse


def print_trans(old: Any, new: Any, indent: int) -> None:
    """A message type's migration, as `rosbag check` lists it."""
    to_txt = f"{new._type} [{new._md5sum}]" if new is not None else "Unknown"
    print("    " * indent + f" * From: {old._type} [{old._md5sum}]")
    print("    " * indent + f"   To:   {to_txt}")


def handle_split(option: Any, opt_str: str, value: Any, parser: Any) -> None:
    """optparse callback of `record --split`, taking the size that old rosbags put after it."""
    parser.values.split = True
    if parser.rargs and parser.rargs[0].isdigit():
        print('Use of "--split <MAX_SIZE>" has been deprecated.  Please use --split --size <MAX_SIZE> or --split '
              "--duration <MAX_DURATION>", file=sys.stderr)
        parser.values.size = int(parser.rargs.pop(0))


def _take_words(parser: Any) -> list[str]:
    words = []
    for arg in parser.rargs:
        if (arg[:2] == "--" and len(arg) > 2) or (arg[:1] == "-" and len(arg) > 1):
            break
        words.append(arg)
    del parser.rargs[:len(words)]
    return words


def handle_topics(option: Any, opt_str: str, value: Any, parser: Any) -> None:
    """optparse callback of `play --topics`: the words up to the next option."""
    parser.values.topics.extend(_take_words(parser))


def handle_pause_topics(option: Any, opt_str: str, value: Any, parser: Any) -> None:
    """optparse callback of `play --pause-topics`: the words up to the next option."""
    parser.values.pause_topics.extend(_take_words(parser))


class ProgressMeter:
    """The `path  42%  1.2 MB / 3.0 MB 00:02 ETA` line rosbag rewrites as it works through a bag."""

    def __init__(self, path: str, bytes_total: float, refresh_rate: float = 1.0) -> None:
        self.path = path
        self.bytes_total = bytes_total
        self.refresh_rate = refresh_rate
        self.elapsed = 0.0
        self.update_elapsed = 0.0
        self.bytes_read = 0.0
        self.start_time = time.time()
        self._update_progress()

    def step(self, bytes_read: float, force_update: bool = False) -> None:
        self.bytes_read = bytes_read
        self.elapsed = time.time() - self.start_time
        if force_update or self.elapsed - self.update_elapsed > self.refresh_rate:
            self._update_progress()
            self.update_elapsed = self.elapsed

    def _update_progress(self) -> None:
        max_path_len = self.terminal_width() - 37
        path = self.path if len(self.path) <= max_path_len else "..." + self.path[-max_path_len + 3:]
        read_text = self._human_readable_size(float(self.bytes_read))
        total_text = self._human_readable_size(float(self.bytes_total))
        if self.bytes_read < self.bytes_total:
            fraction = float(self.bytes_read) / self.bytes_total
            eta_text = "--:--"
            if fraction > 0.0:
                eta = self.elapsed * (1.0 / fraction - 1.0)
                if eta / 60 <= 99:
                    eta_text = f"{int(eta / 60):02d}:{int(eta % 60):02d}"
            pct = int(100.0 * fraction)
            progress = f"{path:<{max_path_len}} {pct:3d}% {read_text:>8} / {total_text:>8} {eta_text} ETA"
        else:
            elapsed = f"{int(self.elapsed / 60):02d}:{int(self.elapsed % 60):02d}"
            progress = f"{path:<{max_path_len}} 100% {total_text:>19} {elapsed}    "
        print("\r", progress, end="")
        sys.stdout.flush()

    def _human_readable_size(self, size: float) -> str:
        for suffix in ("KB", "MB", "GB", "TB", "PB", "EB", "ZB", "YB"):
            size /= 1024.0
            if size < 1024.0:
                return f"{size:.1f} {suffix}"
        raise ValueError("number too large")

    def finish(self) -> None:
        self.step(self.bytes_total, force_update=True)
        print()

    @staticmethod
    def terminal_width() -> int:
        """stdout's terminal's width, else COLUMNS, else 80."""
        width = shutil.get_terminal_size((0, 0)).columns
        if width <= 0:
            with contextlib.suppress(KeyError, ValueError):
                width = int(os.environ["COLUMNS"])
        return width if width > 0 else 80


class RosbagCmds(UserDict[str, Callable[[list[str]], Any]]):
    """The subcommands by name, with their one-line descriptions, and `help`."""

    def __init__(self) -> None:
        super().__init__()
        self._description: dict[str, str] = {}
        self["help"] = self.help_cmd

    def add_cmd(self, name: str, function: Callable[[list[str]], Any], description: str) -> None:
        self[name] = function
        self._description[name] = description

    def get_valid_cmds(self) -> str:
        text = "Available subcommands:\n"
        for name in sorted(self.keys()):
            text += f"   {name}  "
            if name in self._description:
                text += f"\t{self._description[name]}"
            text += "\n"
        return text

    def help_cmd(self, argv: list[str]) -> None:
        argv = [a for a in argv if a not in ("-h", "--help")]
        if not argv:
            print("Usage: rosbag <subcommand> [options] [args]\n")
            print("A bag is a file format in ROS for storing ROS message data. The rosbag command can record, "
                  "replay and manipulate bags.\n")
            print(self.get_valid_cmds())
            print("For additional information, see http://wiki.ros.org/rosbag\n")
            return
        if argv[0] in self:
            self[argv[0]](["-h"])
        else:
            print(f"Unknown command: '{argv[0]}'", file=sys.stderr)
            print(self.get_valid_cmds(), file=sys.stderr)


def change_compression_op(inbag: Bag, outbag: Bag, compression: str, quiet: bool) -> None:
    """Copy every message of `inbag` into `outbag` with `compression`."""
    outbag.compression = compression
    meter = None if quiet else ProgressMeter(outbag.filename or "", inbag.get_compression_info().uncompressed)
    total_bytes = 0
    for topic, msg, t, conn_header in inbag.read_messages(raw=True, return_connection_header=True):
        outbag.write(topic, msg, t, raw=True, connection_header=conn_header)
        if meter is not None:
            total_bytes += len(msg[1])
            meter.step(total_bytes)
    if meter is not None:
        meter.finish()


def reindex_op(inbag: Bag, outbag: Bag, quiet: bool) -> None:
    """Rebuild `outbag`'s index (a copy of `inbag` opened for appending with allow_unindexed)."""
    meter = None if quiet else ProgressMeter(outbag.filename or "", outbag.size)
    try:
        for offset in outbag.reindex():
            if meter is not None:
                meter.step(offset)
    except (ROSBagEncryptNotSupportedException, ROSBagEncryptException):
        raise
    except Exception:  # rosbag's: a bag that cannot be reindexed further keeps what was found
        pass
    if meter is not None:
        meter.finish()


def bag_op(inbag_filenames: Sequence[str], allow_unindexed: bool, open_inbag: bool, copy_fn: Callable[[Bag], bool],
           op: Callable[..., None], output_dir: str | None = None, force: bool = False, quiet: bool = False) -> None:
    """Run `op(inbag, outbag, quiet=...)` on each bag, writing next to it (`output_dir`: there);
    a bag rewritten in place is first kept as `name.orig.bag`. Errors are said per bag."""
    for inbag_filename in inbag_filenames:
        copy = False
        if open_inbag:
            try:
                with Bag(inbag_filename, "r", allow_unindexed=allow_unindexed) as inbag:
                    copy = copy_fn(inbag)
            except ROSBagUnindexedException:
                print(f"ERROR bag unindexed: {inbag_filename}.  Run rosbag reindex.", file=sys.stderr)
                continue
            except (ROSBagException, OSError) as ex:
                print(f"ERROR reading {inbag_filename}: {ex}", file=sys.stderr)
                continue
        outbag_filename = (inbag_filename if output_dir is None
                           else os.path.join(output_dir, os.path.split(inbag_filename)[1]))
        backup_filename = None
        if outbag_filename == inbag_filename:
            stem, extension = os.path.splitext(inbag_filename)
            backup_filename = f"{stem}.orig{extension}"
            if not force and os.path.exists(backup_filename):
                if not quiet:
                    print(f"Skipping {inbag_filename}. Backup path {backup_filename} already exists.",
                          file=sys.stderr)
                continue
            try:
                if copy:
                    shutil.copy(inbag_filename, backup_filename)
                else:
                    os.rename(inbag_filename, backup_filename)
            except OSError as ex:
                print(f"ERROR {'copying' if copy else 'moving'} {inbag_filename} to {backup_filename}: {ex}",
                      file=sys.stderr)
                continue
            source_filename = backup_filename
        elif copy:
            shutil.copy(inbag_filename, outbag_filename)
            source_filename = outbag_filename
        else:
            source_filename = inbag_filename
        try:
            _run_op(op, source_filename, outbag_filename, open_inbag, copy, allow_unindexed, quiet)
        except KeyboardInterrupt:
            if backup_filename is not None:
                try:
                    if copy:
                        os.remove(backup_filename)
                    else:
                        os.rename(backup_filename, inbag_filename)
                except OSError as ex:
                    print(f"ERROR {'removing' if copy else 'moving'} {backup_filename} to {inbag_filename}: {ex}",
                          file=sys.stderr)
                    break
        except (ROSBagException, OSError) as ex:
            print(f"ERROR operating on {inbag_filename}: {ex}", file=sys.stderr)


def _run_op(op: Callable[..., None], source_filename: str, outbag_filename: str, open_inbag: bool, copy: bool,
            allow_unindexed: bool, quiet: bool) -> None:
    inbag = Bag(source_filename, "r", allow_unindexed=allow_unindexed) if open_inbag else None
    try:
        try:
            outbag = (Bag(outbag_filename, "a", allow_unindexed=allow_unindexed) if copy
                      else Bag(outbag_filename, "w"))
        except (ROSBagException, OSError) as ex:
            print(f"ERROR writing to {outbag_filename}: {ex}", file=sys.stderr)
            return
        try:
            op(inbag if inbag is not None else source_filename, outbag, quiet=quiet)
        except ROSBagException as ex:
            print(f"\nERROR operating on {source_filename}: {ex}", file=sys.stderr)
        finally:
            outbag.close()
    finally:
        if inbag is not None:
            inbag.close()
