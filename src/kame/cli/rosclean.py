"""rosclean: check and purge the ROS log folders, as rosclean 1.15 does.

    rosclean check              disk use per folder, as `du -sh` prints it
    rosclean purge [-y] [--size MB]

The folders are the log folder (ROS_LOG_DIR, else ROS_HOME/log, ROS_HOME defaulting to
~/.ros), labelled `ROS node logs`, and ROS_HOME/rosmake (`rosmake logs`), when they exist.
purge asks `(y/n)?` before deleting unless -y; the end of input counts as no (the real one
would ask forever). Sizes are computed here, as du counts them (allocated blocks for check,
apparent bytes for --size), with no du process.
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
from collections.abc import Sequence
from fractions import Fraction
from pathlib import Path


def ros_home() -> Path:
    return Path(os.environ.get("ROS_HOME") or os.path.join(os.path.expanduser("~"), ".ros"))


def log_dir() -> Path:
    value = os.environ.get("ROS_LOG_DIR")
    return Path(value) if value else ros_home() / "log"


def check_dirs() -> list[tuple[Path, str]]:
    dirs = [(log_dir(), "ROS node logs"), (ros_home() / "rosmake", "rosmake logs")]
    return [(d, label) for d, label in dirs if d.is_dir()]


def _entries(top: Path) -> list[os.stat_result]:
    """lstat of `top` and everything below it, hard links counted once (as du does)."""
    stats = []
    seen: set[tuple[int, int]] = set()
    try:
        first = os.lstat(top)
    except OSError:
        return []
    stats.append(first)
    for folder, dirnames, filenames in os.walk(top):
        for name in [*dirnames, *filenames]:
            try:
                st = os.lstat(os.path.join(folder, name))
            except OSError:
                continue
            if st.st_nlink > 1 and not os.path.isdir(os.path.join(folder, name)):
                key = (st.st_dev, st.st_ino)
                if key in seen:
                    continue
                seen.add(key)
            stats.append(st)
    return stats


def disk_usage(top: Path) -> int:
    """Bytes allocated (`du -s` in bytes)."""
    return sum(st.st_blocks * 512 for st in _entries(top))


def apparent_size(top: Path) -> int:
    """Apparent size in bytes (`du -sb`)."""
    return sum(st.st_size for st in _entries(top))


def human_size(size: int) -> str:
    """`du -h`: powers of 1024, rounded up, one decimal below 10."""
    units = "KMGTPEZY"
    if size < 1024:
        return str(size)
    value = Fraction(size)
    exponent = 0
    while value >= 1024 and exponent < len(units):
        value /= 1024
        exponent += 1
    if value < 10:
        tenths = -(-value * 10 // 1)  # ceiling
        if tenths < 100:
            return f"{tenths // 10}.{tenths % 10}{units[exponent - 1]}"
        value = Fraction(10)
    whole = -(-value // 1)
    if whole >= 1024 and exponent < len(units):
        return f"1.0{units[exponent]}"
    return f"{whole}{units[exponent - 1]}"


def _quote(s: str) -> str:
    return f'"{s}"' if " " in s else s


def _ask(comment: str) -> bool:
    sys.stdout.write(f"Okay to perform:\n\n{comment}\n(y/n)?\n")
    sys.stdout.flush()
    while True:
        line = sys.stdin.readline()
        if not line:
            return False
        answer = line.strip().lower()
        if answer in ("y", "n"):
            return answer == "y"


def _remove(path: Path) -> None:
    try:
        if path.is_dir() and not path.is_symlink():
            shutil.rmtree(path)
        elif path.exists() or path.is_symlink():
            path.unlink()
    except OSError:
        print("FAILED to execute command", file=sys.stderr)


def cmd_check(args: argparse.Namespace) -> None:
    for d, label in check_dirs():
        print(f"{human_size(disk_usage(d))} {label}")


def cmd_purge(args: argparse.Namespace) -> None:
    for d, label in check_dirs():
        if not args.size:
            print(f"Purging {label}.")
            if args.y:
                _remove(d)
            else:
                print("PLEASE BE CAREFUL TO VERIFY THE COMMAND BELOW!")
                if _ask(" ".join(_quote(s) for s in ("rm", "-rf", str(d)))):
                    _remove(d)
            continue
        limit = args.size * 1024 * 1024
        entries = sorted(os.listdir(d), key=lambda f: os.path.getmtime(d / f))
        size = apparent_size(d)
        if size <= limit:
            print(f"Directory size of {label} is {size // 1024 // 1024} MB which is already below the requested "
                  f"threshold of {args.size} MB.")
            continue
        print(f"Purging {label} until directory size is at most {args.size} MB (currently {size // 1024 // 1024} MB).")
        if not args.y:
            print("PLEASE BE CAREFUL TO VERIFY THE COMMAND BELOW!")
            if not _ask(f"Purge some of old logs in {d}"):
                return
        for name in entries:
            if size <= limit:
                break
            path = d / name
            size -= apparent_size(path)
            _remove(path)


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="rosclean")
    subparsers = parser.add_subparsers(required=True, dest="{check,purge}")
    check = subparsers.add_parser("check", help="Check usage of log files")
    check.set_defaults(func=cmd_check)
    purge = subparsers.add_parser("purge", help="Remove log files")
    purge.set_defaults(func=cmd_purge)
    purge.add_argument("-y", action="store_true", default=False,
                       help="CAUTION: automatically confirms all questions to delete files")
    purge.add_argument("--size", action="store", default=None, type=int,
                       help="Maximum total size in MB to keep when deleting old files")
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    args = _parser().parse_args(sys.argv[1:] if argv is None else argv)
    try:
        args.func(args)
    except KeyboardInterrupt:
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
