"""Shell integration: the setup files a user sources, and the helpers they call.

setup.bash / setup.zsh / setup.sh (in this folder) set the ROS 1 environment; rosbash.sh
defines roscd & co; completion.bash registers tab completion. `kame-setup --path` (or
`python -m kame.shell --path`) prints where setup.bash is, so a user writes
`source "$(kame-setup --path)"` or puts that path in ~/.bashrc.
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from pathlib import Path

SHELL_DIR = Path(__file__).resolve().parent
SHELLS = ("bash", "zsh", "sh")


def setup_file(shell: str = "bash") -> Path:
    """The setup file a user of `shell` sources."""
    if shell not in SHELLS:
        raise ValueError(f"unknown shell {shell!r} (one of {', '.join(SHELLS)})")
    return SHELL_DIR / f"setup.{shell}"


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="kame-setup",
        description="Print the path of kame's setup file; source it for the ROS 1 environment, "
        "roscd/rosls/rosed/roscp/roscat and tab completion: source \"$(kame-setup --path)\"",
    )
    parser.add_argument("--path", action="store_true", help="print the setup file's path (the default)")
    parser.add_argument("--shell", choices=SHELLS, default="bash", help="which shell's setup file (default bash)")
    parser.add_argument("--dir", action="store_true", help="print the folder holding the setup files")
    args = parser.parse_args(argv)
    print(SHELL_DIR if args.dir else setup_file(args.shell))
    return 0


__all__ = ["SHELL_DIR", "main", "setup_file"]
