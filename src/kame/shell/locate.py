"""What roscd, rosls, rospd, rosed, roscp and roscat look up: packages, keywords, files.

Rules (rosbash's _ros_location_find and _roscmd):
- A location is a ROS_LOCATIONS keyword (`key=dir:key2=dir2`, `~` expanded), `log` (the
  running master's log folder: $ROS_LOG_DIR or $ROS_HOME/log or ~/.ros/log, plus /run_id;
  the log folder itself and "No active roscore" on stderr when no master answers),
  `test_results`, or a package found as rospack finds it (kame.msg.catalog).
- `PKG/sub/dir` is the package folder plus the sub-path (which need not exist: cd says so).
- A file in a package is searched below the package folder (following symlinks, skipping
  hidden folders and the package's build/), and in lib/PKG of the catkin workspaces in
  CMAKE_PREFIX_PATH.

Commands (`python -m kame.shell.locate ...`), all printing on stdout, status 1 when not found:
`find LOCATION[/sub]`, `locations` (every completable location), `file PKG NAME` (every
match, one a line), `subdirs LOCATION[/sub]`, `files PKG` (every file name in the package).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path

from kame import environ
from kame.msg.catalog import Package, find_packages, package_path_roots, shipped_programs


def packages(env: Mapping[str, str] | None = None) -> dict[str, Package]:
    env = os.environ if env is None else env
    return find_packages(package_path_roots(env.get("ROS_PACKAGE_PATH", "")))


def ros_locations(env: Mapping[str, str]) -> dict[str, str]:
    found: dict[str, str] = {}
    for item in env.get("ROS_LOCATIONS", "").split(":"):
        key, sep, folder = item.partition("=")
        if sep and key:
            found.setdefault(key, os.path.expanduser(folder))
    return found


def ros_log_dir(env: Mapping[str, str]) -> str:
    if env.get("ROS_LOG_DIR"):
        return env["ROS_LOG_DIR"]
    home = env.get("ROS_HOME") or os.path.join(os.path.expanduser("~"), ".ros")
    return os.path.join(home, "log")


def run_id(env: Mapping[str, str]) -> str | None:
    """The master's /run_id, or None when no master answers quickly."""
    from kame.node.master_proxy import MasterError, MasterProxy

    uri = environ.master_uri(env)
    try:
        proxy = MasterProxy(uri, "/roslaunch", timeout=2.0)
    except ValueError:
        return None
    try:
        value = proxy.call("getParam", "/run_id")
    except (OSError, MasterError, ValueError):
        return None
    except Exception:  # a garbled answer is no answer
        return None
    finally:
        proxy.close()
    return str(value) if value else None


def test_results_dir(env: Mapping[str, str]) -> str:
    if env.get("ROS_TEST_RESULTS_DIR"):
        return env["ROS_TEST_RESULTS_DIR"]
    home = env.get("ROS_HOME") or os.path.join(os.path.expanduser("~"), ".ros")
    return os.path.join(home, "test_results")


def find_location(name: str, env: Mapping[str, str] | None = None) -> str | None:
    env = os.environ if env is None else env
    keywords = ros_locations(env)
    if name in keywords:
        return keywords[name]
    if name == "log":
        log_dir = ros_log_dir(env)
        rid = run_id(env)
        if rid is None:
            print("No active roscore", file=sys.stderr)
            return log_dir
        return os.path.join(log_dir, rid)
    if name == "test_results":
        return test_results_dir(env)
    package = packages(env).get(name)
    return str(package.path) if package else None


def resolve(arg: str, env: Mapping[str, str] | None = None) -> str | None:
    """LOCATION[/sub/path] as a folder path (the sub-path as typed), None if unknown."""
    name, sep, rest = arg.partition("/")
    base = find_location(name, env)
    if base is None:
        return None
    return base + "/" + rest if sep else base


def list_locations(env: Mapping[str, str] | None = None) -> list[str]:
    env = os.environ if env is None else env
    return sorted({*packages(env), "log", "test_results", *ros_locations(env)})


def _walk_files(root: Path, skip: Path | None) -> Iterator[Path]:
    for folder, dirs, files in os.walk(root, followlinks=True):
        here = Path(folder)
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and (skip is None or here / d != skip))
        for name in sorted(files):
            if not name.startswith("."):
                yield here / name


def libexec_dirs(package: str, env: Mapping[str, str]) -> list[Path]:
    found = []
    for prefix in env.get("CMAKE_PREFIX_PATH", "").split(os.pathsep):
        if prefix and (Path(prefix) / ".catkin").is_file():
            candidate = Path(prefix) / "lib" / package
            if candidate.is_dir():
                found.append(candidate)
    return found or shipped_programs(package)


def package_roots(package: str, env: Mapping[str, str]) -> list[tuple[Path, Path | None]]:
    """(folder, build folder to skip) for a package: catkin libexec folders, then its source."""
    roots: list[tuple[Path, Path | None]] = [(d, None) for d in libexec_dirs(package, env)]
    found = packages(env).get(package)
    if found is not None:
        roots.append((found.path, found.path / "build"))
    return roots


def find_files(package: str, name: str, env: Mapping[str, str] | None = None) -> list[str] | None:
    """Every file called `name` in the package (None: no such package)."""
    env = os.environ if env is None else env
    roots = package_roots(package, env)
    if not roots:
        return None
    hits: list[str] = []
    for root, skip in roots:
        for path in _walk_files(root, skip):
            if path.name == name and str(path) not in hits:
                hits.append(str(path))
    return hits


def package_file_names(package: str, env: Mapping[str, str] | None = None, executable: bool = False) -> list[str]:
    env = os.environ if env is None else env
    names: set[str] = set()
    for root, skip in package_roots(package, env):
        for path in _walk_files(root, skip):
            if not executable or (os.access(path, os.X_OK) and path.is_file()):
                names.add(path.name)
    return sorted(names)


def subdirs(arg: str, env: Mapping[str, str] | None = None) -> list[str]:
    """Completions of LOCATION/sub/pa: `LOCATION/sub/path/` for each matching folder."""
    name, _, rest = arg.partition("/")
    base = find_location(name, env)
    if base is None:
        return []
    parent, _, _ = rest.rpartition("/")
    folder = Path(base, parent) if parent else Path(base)
    prefix = f"{name}/{parent}/" if parent else f"{name}/"
    try:
        children = sorted(c.name for c in folder.iterdir() if c.is_dir() and not c.name.startswith("."))
    except OSError:
        return []
    return [prefix + c + "/" for c in children]


def main(argv: Sequence[str] | None = None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    command, rest = (args[0], args[1:]) if args else ("", [])
    if command == "find" and len(rest) == 1:
        found = resolve(rest[0])
        if found is None:
            return 1
        print(found)
    elif command == "locations":
        print("\n".join(list_locations()))
    elif command == "file" and len(rest) == 2:
        hits = find_files(rest[0], rest[1])
        if hits is None:
            return 2
        if hits:
            print("\n".join(hits))
        return 0 if hits else 1
    elif command == "subdirs" and len(rest) == 1:
        print("\n".join(subdirs(rest[0])))
    elif command == "files" and len(rest) == 1:
        print("\n".join(package_file_names(rest[0])))
    else:
        print("usage: python -m kame.shell.locate find|locations|file|subdirs|files ...", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
