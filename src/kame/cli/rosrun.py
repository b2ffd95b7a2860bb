"""rosrun: run an executable of a ROS package, as rosbash's rosrun does.

    rosrun [--prefix cmd] [--debug] PACKAGE EXECUTABLE [ARGS]

Where it looks, as the real one: the catkin workspaces' lib/PACKAGE, share/PACKAGE and source
folders (`catkin_find --without-underlays --libexec --share`), kame's own lib/PACKAGE
(kame/lib, where an installed ROS keeps a package's programs), then the package folder
(`rospack find`), searched recursively, following symbolic links, for a regular file of that
name with an execute bit (not below the package's build/ folder). A name with a slash is a
path inside the package folder. Two hits, one a workspace relay and one in a share/source
folder: the relay wins; more hits: a numbered menu. What kame adds, to be friendly:
- Python programs (a python shebang, or a .py file without one) run with kame's interpreter,
  whatever their shebang names, so they import kame's rospy.
- A .py file found but not executable is still run, with a note saying to chmod +x it.
- Entry points: `[kame.rosrun]` entries named `PACKAGE/EXECUTABLE`, and console scripts whose
  module lives in the Python package named PACKAGE, run when no file is found.
Messages and exit statuses are the real ones (2: unknown package, 3: no such executable); the
process then becomes the program (exec), so its PID and Ctrl-C behave as with the real rosrun.
"""

from __future__ import annotations

import fnmatch
import os
import re
import shlex
import sys
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path

from kame.catkin.executables import command_for, is_executable
from kame.msg.catalog import find_packages, package_path_roots, shipped_programs

USAGE = """Usage: rosrun [--prefix cmd] [--debug] PACKAGE EXECUTABLE [ARGS]
  rosrun will locate PACKAGE and try to find
  an executable named EXECUTABLE in the PACKAGE tree.
  If it finds it, it will run it with ARGS."""
ENTRY_POINT_GROUP = "kame.rosrun"


@dataclass(frozen=True)
class EntryPointTarget:
    name: str
    value: str
    group: str
    script: Path | None  # the installed console script, when there is one


def catkin_dirs(package: str, kinds: Sequence[str] = ("lib", "libexec", "share")) -> list[Path]:
    """`catkin_find --without-underlays --libexec --share PACKAGE`: the first workspace on
    CMAKE_PREFIX_PATH (one with a .catkin marker) holding the package, its folders for it."""
    for entry in os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep):
        workspace = Path(entry) if entry else None
        if workspace is None or not (workspace / ".catkin").is_file():
            continue
        found = [workspace / kind / package for kind in kinds if (workspace / kind / package).exists()]
        if "share" in kinds:
            found += _source_dirs(workspace, package)
        if found:
            return found
    return []


def _source_dirs(workspace: Path, package: str) -> list[Path]:
    try:
        data = (workspace / ".catkin").read_text()
    except OSError:
        return []
    sources = dict.fromkeys(os.path.realpath(p) for p in data.split(";") if p)
    found = []
    for source in sources:
        pkg = find_packages([Path(source)]).get(package)
        if pkg is not None:
            found.append(pkg.path)
    return found


def _walk_files(top: Path, pattern: str) -> Iterator[Path]:
    """`find -L top -name pattern -type f`, in name order, symbolic link loops skipped."""
    visited: set[str] = set()

    def walk(folder: Path) -> Iterator[Path]:
        real = os.path.realpath(folder)
        if real in visited:
            return
        visited.add(real)
        try:
            entries = sorted(os.scandir(folder), key=lambda e: e.name)
        except OSError:
            return
        for entry in entries:
            path = Path(entry.path)
            try:
                is_dir = entry.is_dir()  # follows symbolic links
                is_file = entry.is_file()
            except OSError:
                continue
            if is_file and fnmatch.fnmatchcase(entry.name, pattern):
                yield path
            if is_dir:
                yield from walk(path)

    if top.is_file():
        if fnmatch.fnmatchcase(top.name, pattern):
            yield top
    elif top.is_dir():
        yield from walk(top)


def find_executables(dirs: Sequence[Path], pkgdir: Path | None, name: str) -> list[Path]:
    build = re.compile(".*" + re.escape(str(pkgdir)) + "/build/.*") if pkgdir is not None else None
    hits: dict[str, Path] = {}
    for top in dirs:
        for path in _walk_files(top, name):
            if is_executable(path) and not (build is not None and build.fullmatch(str(path))):
                hits.setdefault(str(path), path)
    return list(hits.values())


def find_named(pkgdir: Path, name: str) -> list[Path]:
    """`find -H pkgdir -name name`: files and folders of that name, links not followed."""
    found = []
    for folder, dirnames, filenames in os.walk(pkgdir):
        dirnames.sort()
        for entry in sorted([*dirnames, *filenames]):
            if fnmatch.fnmatchcase(entry, name):
                found.append(Path(folder, entry))
    return found


def entry_point(package: str, name: str) -> EntryPointTarget | None:
    """An installed entry point that runs `name` of ROS package `package`, if there is one."""
    eps = metadata.entry_points()
    for ep in eps.select(group=ENTRY_POINT_GROUP, name=f"{package}/{name}"):
        return EntryPointTarget(name, ep.value, ep.group, None)
    for ep in eps.select(group="console_scripts", name=name):
        module = ep.value.partition(":")[0].strip()
        if module == package or module.startswith(package + "."):
            script = Path(sys.executable).parent / name
            return EntryPointTarget(name, ep.value, ep.group, script if script.is_file() else None)
    return None


def _entry_point_command(target: EntryPointTarget) -> list[str]:
    if target.script is not None:
        return [sys.executable, str(target.script)]
    code = ("import sys; from importlib.metadata import EntryPoint; "
            f"sys.argv[0] = {target.name!r}; "
            f"sys.exit(EntryPoint({target.name!r}, {target.value!r}, {target.group!r}).load()())")
    return [sys.executable, "-c", code]


def _choose(paths: Sequence[Path]) -> Path | None:
    """bash's `select` menu: numbered choices and a `#? ` prompt on stderr, a number from stdin."""
    for i, path in enumerate(paths, 1):
        print(f"{i}) {path}", file=sys.stderr)
    print("#? ", end="", file=sys.stderr, flush=True)
    answer = sys.stdin.readline().strip()
    if answer.isdigit() and 1 <= int(answer) <= len(paths):
        return paths[int(answer) - 1]
    return None


def _inside(path: Path, folders: Sequence[Path]) -> bool:
    return any(str(path).startswith(str(folder)) for folder in folders)


class _Exit(Exception):
    def __init__(self, status: int) -> None:
        super().__init__(status)
        self.status = status


def resolve(package: str, name: str, debug: bool) -> list[str]:
    """The command that runs `name` of `package`; prints rosrun's messages and raises _Exit."""
    def say(text: str) -> None:
        if debug:
            print("[rosrun]", text)

    libexec = catkin_dirs(package) or shipped_programs(package)  # kame's lib/<package>: an installed ROS's
    say("Looking in catkin libexec dirs: \n" + "\n".join(str(d) for d in libexec))
    pkg = find_packages(package_path_roots()).get(package)
    pkgdir = Path(os.path.abspath(pkg.path)) if pkg is not None else None
    say(f"Looking in rospack dir: {pkgdir or ''}")
    target = entry_point(package, name) if "/" not in name else None
    if pkgdir is None and target is None:
        print(f"[rospack] Error: package '{package}' not found", file=sys.stderr)
    if not libexec and pkgdir is None and target is None:
        raise _Exit(2)
    if "/" in name:
        path = (pkgdir or Path("")) / name
        say(f"Path given. Looing for {path}")
        if not (path.is_file() and is_executable(path)):
            print(f"[rosrun] Couldn't find executable named {path}")
            raise _Exit(3)
        return command_for(path)
    say(f"Searching for {name} with permissions /111")
    hits = find_executables([*libexec, *([pkgdir] if pkgdir else [])], pkgdir, name)
    if target is not None and not hits:
        return _entry_point_command(target)
    if not hits:
        others = find_named(pkgdir, name) if pkgdir is not None else []
        python_files = [p for p in others if p.is_file() and p.suffix == ".py"]
        if len(others) == 1 and python_files:
            print(f"[rosrun] {others[0]} is not executable; running it with {sys.executable} "
                  f"(chmod +x it to run it directly)", file=sys.stderr)
            return [sys.executable, str(others[0])]
        print(f"[rosrun] Couldn't find executable named {name} below {pkgdir or ''}")
        if others:
            print("[rosrun] Found the following, but they're either not files,")
            print("[rosrun] or not executable:")
            for other in others:
                print(f"[rosrun]   {other}")
        raise _Exit(3)
    if len(hits) == 2:
        share = catkin_dirs(package, ("share",))
        first, second = (_inside(h, share) for h in hits)
        if not first and second:
            say(f"Assuming {hits[0]} is a devel-space relay for {hits[1]}")
            hits = hits[:1]
        elif first and not second:
            say(f"Assuming {hits[1]} is a devel-space relay for {hits[0]}")
            hits = hits[1:]
    if len(hits) > 1:
        print("[rosrun] You have chosen a non-unique executable, please pick one of the following:")
        sys.stdout.flush()
        chosen = _choose(hits)
        if chosen is None:
            raise _Exit(127)
        return command_for(chosen)
    return command_for(hits[0])


def main(argv: Sequence[str] | None = None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    prefix = ""
    debug = False
    while args:
        if args[0] in ("--help", "-h"):
            print(USAGE)
            return 0
        if args[0] in ("--prefix", "-p"):
            prefix = args[1] if len(args) > 1 else ""
            args = args[2:]
        elif args[0] in ("--debug", "-d"):
            debug = True
            args = args[1:]
        else:
            break
    if len(args) < 2:
        print(USAGE)
        return 0
    package, name, rest = args[0], args[1], args[2:]
    if name.endswith("/"):
        print(f"Invalid filename:  {name}")
        return 1
    try:
        command = resolve(package, name, debug)
    except _Exit as exc:
        return exc.status
    except KeyboardInterrupt:
        return 130
    argv_out = [*shlex.split(prefix), *command, *rest]
    if debug:
        print("[rosrun]", f"Running {prefix} {' '.join(command)}", *rest)
    sys.stdout.flush()
    sys.stderr.flush()
    try:
        os.execvp(argv_out[0], argv_out)
    except OSError as exc:
        if exc.errno == 8 and not prefix:  # ENOEXEC: no #! line; bash runs such a file as a script
            try:
                os.execv("/bin/sh", ["/bin/sh", *argv_out])
            except OSError:
                pass
        print(f"[rosrun] {argv_out[0]}: {exc.strerror}", file=sys.stderr)
        return 127 if isinstance(exc, FileNotFoundError) else 126
    return 0  # not reached


if __name__ == "__main__":
    sys.exit(main())
