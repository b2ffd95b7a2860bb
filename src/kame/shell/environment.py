"""The environment a sourced setup file gives: kame's ROS_* variables and workspace overlays.

Rules (as catkin's setup files and /opt/ros/noetic/setup.bash behave):
- Sourcing any setup file first rolls back every catkin workspace found in CMAKE_PREFIX_PATH
  (a folder holding a `.catkin` marker): its devel folder, its bin/ on PATH, its Python site
  folder on PYTHONPATH, its lib/ folders on LD_LIBRARY_PATH and PKG_CONFIG_PATH and its source
  folders on ROS_PACKAGE_PATH go. So sourcing workspace A
  and then workspace B leaves only B (and what B was built on).
- Then kame's base: ROS_MASTER_URI (kept if set), ROS_DISTRO, ROS_ROOT, ROS_ETC_DIR,
  ROS_VERSION, ROS_PYTHON_VERSION, the interpreter's bin/ first on PATH, kame's share folder
  last on ROS_PACKAGE_PATH.
- Then each prefix the workspace was built on (the CMAKE_PREFIX_PATH of its build: catkin
  devel spaces and other prefixes), underlays first, and the workspace's devel space last:
  the prefix on CMAKE_PREFIX_PATH; its bin/ on PATH, lib/python3/dist-packages on PYTHONPATH,
  lib/ (where catkin's CMake puts the C++ packages' libraries) on LD_LIBRARY_PATH and
  lib/pkgconfig on PKG_CONFIG_PATH, each when it exists (as catkin's _setup_util.py); a
  devel space's source folders on ROS_PACKAGE_PATH (each prepended, so the last sourced
  wins); ROSLISP_PACKAGE_DIRECTORIES lists devel/share/common-lisp of each devel space on
  CMAKE_PREFIX_PATH, in its order, as roslisp's environment hook does.

`python -m kame.shell.environment --python P [--workspaces DEVEL:DEVEL]` prints the result as
`export`/`unset` lines for `eval` in sh, bash and zsh.
"""

from __future__ import annotations

import argparse
import os
import shlex
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path

from kame import environ

DEFAULT_MASTER_URI = environ.SETUP_MASTER_URI
KAME_DIR = Path(__file__).resolve().parent.parent
SHARE_DIR = KAME_DIR / "share"
PYTHON_SITE = "lib/python3/dist-packages"
PATH_VARIABLES = ("CMAKE_PREFIX_PATH", "LD_LIBRARY_PATH", "PATH", "PKG_CONFIG_PATH", "PYTHONPATH", "ROS_PACKAGE_PATH")
# catkin's _setup_util.py (ENV_VAR_SUBFOLDERS): the folders of a prefix a variable gets, each only
# when it exists
SUBFOLDERS = {
    "LD_LIBRARY_PATH": ("lib", "lib/x86_64-linux-gnu"),
    "PATH": ("bin",),
    "PKG_CONFIG_PATH": ("lib/pkgconfig", "lib/x86_64-linux-gnu/pkgconfig"),
    "PYTHONPATH": (PYTHON_SITE,),
}
LISP_FOLDER = "share/common-lisp"  # genlisp's output folder, which roslisp's environment hook lists
CATKIN_MARKER = ".catkin"


def _split(value: str | None) -> list[str]:
    return [p for p in (value or "").split(os.pathsep) if p]


def _norm(path: str) -> str:
    return os.path.normpath(path)


def workspace_sources(devel: Path) -> list[str]:
    """The source folders a devel folder's .catkin marker names (`;`-separated, as catkin)."""
    try:
        text = (devel / CATKIN_MARKER).read_text()
    except OSError:
        return []
    return [p for p in text.strip().split(";") if p]


def is_workspace(path: str) -> bool:
    return os.path.isfile(os.path.join(path, CATKIN_MARKER))


def _remove(entries: list[str], unwanted: set[str]) -> list[str]:
    return [e for e in entries if _norm(e) not in unwanted]


def _prepend(entries: list[str], new: str) -> list[str]:
    return [new, *[e for e in entries if _norm(e) != _norm(new)]]


def _append(entries: list[str], new: str) -> list[str]:
    return [*[e for e in entries if _norm(e) != _norm(new)], new]


def compute(env: Mapping[str, str], python: str, workspaces: Sequence[str] = ()) -> dict[str, str | None]:
    """The variables to set (None: unset) for kame's base plus `workspaces` (the prefixes a devel
    space was built on and the devel space, underlays first)."""
    lists = {name: _split(env.get(name)) for name in PATH_VARIABLES}

    # roll back workspaces sourced before
    old = [p for p in lists["CMAKE_PREFIX_PATH"] if is_workspace(p)]
    for devel in old:
        lists["CMAKE_PREFIX_PATH"] = _remove(lists["CMAKE_PREFIX_PATH"], {_norm(devel)})
        for name, folders in SUBFOLDERS.items():
            lists[name] = _remove(lists[name], {_norm(os.path.join(devel, f)) for f in folders})
        lists["ROS_PACKAGE_PATH"] = _remove(lists["ROS_PACKAGE_PATH"],
                                            {_norm(s) for s in workspace_sources(Path(devel))})

    # kame's base
    result: dict[str, str | None] = {
        "ROS_MASTER_URI": env.get("ROS_MASTER_URI") or DEFAULT_MASTER_URI,
        "ROS_DISTRO": "noetic",
        "ROS_ROOT": str(SHARE_DIR / "ros"),
        "ROS_ETC_DIR": str(KAME_DIR / "etc" / "ros"),
        "ROS_VERSION": "1",
        "ROS_PYTHON_VERSION": "3",
    }
    lists["PATH"] = _prepend(lists["PATH"], os.path.dirname(python))
    lists["ROS_PACKAGE_PATH"] = _append(lists["ROS_PACKAGE_PATH"], str(SHARE_DIR))

    for devel in workspaces:
        lists["CMAKE_PREFIX_PATH"] = _prepend(lists["CMAKE_PREFIX_PATH"], devel)
        for name, folders in SUBFOLDERS.items():
            for folder in reversed(folders):
                if os.path.isdir(os.path.join(devel, folder)):
                    lists[name] = _prepend(lists[name], os.path.join(devel, folder))
        for source in reversed(workspace_sources(Path(devel))):
            lists["ROS_PACKAGE_PATH"] = _prepend(lists["ROS_PACKAGE_PATH"], source)

    for name, entries in lists.items():
        result[name] = os.pathsep.join(entries) if entries else None
    lisp = [os.path.join(p, LISP_FOLDER) for p in lists["CMAKE_PREFIX_PATH"]
            if is_workspace(p) and workspace_sources(Path(p))]
    result["ROSLISP_PACKAGE_DIRECTORIES"] = os.pathsep.join(lisp) if lisp else None
    return result


def shell_lines(changes: Mapping[str, str | None]) -> str:
    lines = []
    for name, value in changes.items():
        lines.append(f"unset {name}" if value is None else f"export {name}={shlex.quote(value)}")
    return "\n".join(lines) + "\n"


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m kame.shell.environment")
    parser.add_argument("--python", default=sys.executable, help="the interpreter whose bin/ goes on PATH")
    parser.add_argument("--workspaces", default="",
                        help="prefixes (devel folders and others), ':'-separated, underlays first")
    args = parser.parse_args(argv)
    sys.stdout.write(shell_lines(compute(os.environ, args.python, _split(args.workspaces))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
