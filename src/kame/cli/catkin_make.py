"""catkin_make: build a catkin workspace into its devel space: C/C++ packages with the real CMake,
Python-only packages by kame without it.

As catkin_make: run in the workspace root (or -C DIR); source space src/, build space
build/, devel space devel/; prints the spaces, the packages in topological order and the
progress; `-DVAR=VALUE` arguments are CMake cache variables (CATKIN_WHITELIST_PACKAGES and
CATKIN_BLACKLIST_PACKAGES are honoured and, as in CMake, remembered in build/kame_cache.txt
until set again, `-DCATKIN_WHITELIST_PACKAGES=""` clears); `--only-pkg-with-deps` and
`--pkg` select packages; make flags (-j, -l) and targets are accepted. Errors are one red
line on stderr, exit 1.

Packages with C/C++ targets, and the workspace packages they depend on, are built as
catkin_make builds them: src/CMakeLists.txt linked to the system's catkin toplevel.cmake,
then `cmake` and `make` in the build space (kame/catkin/cmake.py), with headers for kame's
message packages the system lacks (kame/catkin/cpp_messages.py). The other packages are
kame's: set up in the devel space with no CMake. Where the machine has no C++ toolchain or
roscpp, what to install is said, the Python packages are built, and the exit status is 1.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Callable, Sequence
from pathlib import Path

from kame.catkin.build import PackageResult, build, configure_lines, underlay_prefixes
from kame.catkin.cmake import CMakeBuild, CMakeFailed, inputs_changed, link_toplevel
from kame.catkin.cpp_messages import KameMessageHeaders, MessageHeaderError
from kame.catkin.toolchain import Missing, Toolchain, find_toolchain, missing_components, os_release, prefixes
from kame.catkin.workspace import (
    WorkspaceError,
    WorkspacePackage,
    cmake_list,
    cmake_packages,
    find_workspace_packages,
    select,
    with_dependencies,
)

RED = "\033[31m"
RESET = "\033[0m"
CACHE = "kame_cache.txt"  # not CMakeCache.txt: CMake owns that one where C++ packages are built
KAME_PREFIX = "kame_msgs"  # kame's prefix of C++ message headers in the build space
CACHED = ("CATKIN_WHITELIST_PACKAGES", "CATKIN_BLACKLIST_PACKAGES")
WORKSPACE_MARKER = "# This file currently only serves to mark the location of a catkin workspace for tool integration\n"


class BuildError(Exception):
    pass


def shell_dir() -> Path:
    from kame.shell import SHELL_DIR

    return SHELL_DIR


def read_cache(build_path: Path) -> dict[str, str]:
    values: dict[str, str] = {}
    try:
        lines = (build_path / CACHE).read_text().splitlines()
    except OSError:
        return values
    for line in lines:
        key, sep, value = line.partition("=")
        if sep and not line.startswith(("#", "//")):
            values[key.partition(":")[0]] = value
    return values


def write_cache(build_path: Path, values: dict[str, str]) -> None:
    lines = ["# kame catkin_make cache: CMake cache variables given with -D, remembered between builds\n"]
    lines += [f"{key}:STRING={value}\n" for key, value in sorted(values.items())]
    (build_path / CACHE).write_text("".join(lines))


def split_arguments(argv: Sequence[str]) -> tuple[list[str], dict[str, str], list[str]]:
    """(catkin_make's own arguments, -D cache variables, make arguments and targets)."""
    own: list[str] = []
    defines: dict[str, str] = {}
    make: list[str] = []
    args = list(argv)
    i = 0
    while i < len(args):
        arg = args[i]
        if arg == "--cmake-args":
            for extra in args[i + 1 :]:
                if extra.startswith("-D") and "=" in extra:
                    key, _, value = extra[2:].partition("=")
                    defines[key.partition(":")[0]] = value
            break
        if arg == "--make-args":
            make += args[i + 1 :]
            break
        if arg.startswith("-D") and "=" in arg:
            key, _, value = arg[2:].partition("=")
            defines[key.partition(":")[0]] = value
        elif arg.startswith(("-j", "-l")) or arg in ("--jobs", "--load-average"):
            make.append(arg)
            if arg in ("-j", "-l", "--jobs", "--load-average") and i + 1 < len(args) and args[i + 1].isdigit():
                i += 1
                make.append(args[i])
        else:
            own.append(arg)
        i += 1
    return own, defines, make


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="catkin_make",
        description="Creates the catkin workspace layout and builds its packages into the devel space: "
        "C/C++ packages with CMake and the system's catkin, Python packages by kame. "
        "Any argument starting with -D sets a CMake cache variable "
        '(e.g. -DCATKIN_WHITELIST_PACKAGES="foo;bar", -DCATKIN_BLACKLIST_PACKAGES="foo;bar").',
    )
    p.add_argument("-C", "--directory", default=os.curdir, help="The base path of the workspace (default '.')")
    p.add_argument("--source", help="The path to the source space (default 'workspace_base/src')")
    p.add_argument("--build", help="The path to the build space (default 'workspace_base/build')")
    p.add_argument("--use-ninja", action="store_true", help="Accepted for compatibility")
    p.add_argument("--use-nmake", action="store_true", help="Accepted for compatibility")
    p.add_argument("--use-gmake", action="store_true", help="Accepted for compatibility")
    p.add_argument("--force-cmake", action="store_true", help="Invoke cmake even if it has been executed before")
    p.add_argument("--no-color", action="store_true", help="Disables colored output")
    p.add_argument("--pkg", nargs="+", help="Build specific packages only")
    p.add_argument("--only-pkg-with-deps", nargs="+",
                   help="Whitelist only the specified packages and their dependencies (remembered, like "
                        'CATKIN_WHITELIST_PACKAGES; clear with -DCATKIN_WHITELIST_PACKAGES="")')
    p.add_argument("--override-build-tool-check", action="store_true", help="Build even if another tool built here")
    p.add_argument("targets", nargs="*", help="make targets (all, install, clean, ...)")
    return p


def _path(cwd: str, base: Path, arg: str | None, default: str) -> Path:
    return Path(os.path.abspath(os.path.join(cwd, arg))) if arg else base / default


def _check_tool(space: Path, tool: str, override: bool) -> None:
    marker = space / ".built_by"
    try:
        previous = marker.read_text().strip()
    except OSError:
        previous = ""
    if previous and previous != tool and not override:
        raise BuildError(f"The {space.name} space at '{space}' was previously built by '{previous}'. "
                         f"Please remove the {space.name} space or pick a different {space.name} space.")


def _mark(space: Path, tool: str) -> None:
    space.mkdir(parents=True, exist_ok=True)
    (space / ".built_by").write_text(tool)


def working_directory() -> str:
    """$PWD when it names the current folder (so symlinked workspaces keep their name)."""
    pwd = os.environ.get("PWD")
    if pwd and os.path.isdir(pwd) and os.path.samefile(pwd, os.curdir):
        return pwd
    return os.getcwd()


def run(argv: Sequence[str]) -> int:
    own, defines, make_args = split_arguments(argv)
    args = parser().parse_args(own)
    color = not args.no_color

    def say(line: str = "") -> None:
        print(line, flush=True)

    cwd = working_directory()
    base = Path(os.path.abspath(os.path.join(cwd, args.directory)))
    if not base.exists():
        raise BuildError(f'The specified base path "{base}" does not exist')
    say(f"Base path: {base}")
    if (base / "package.xml").exists():
        raise BuildError(f'The specified base path "{base}" contains a package but "catkin_make" must be invoked '
                         "in the root of workspace")
    source = _path(cwd, base, args.source, "src")
    if not source.exists():
        raise BuildError(f'The specified source space "{source}" does not exist')
    say(f"Source space: {source}")
    build_path = _path(cwd, base, args.build, "build")
    say(f"Build space: {build_path}")
    _check_tool(build_path, "catkin_make", args.override_build_tool_check)
    devel = Path(os.path.abspath(os.path.join(cwd, defines.pop("CATKIN_DEVEL_PREFIX")))) \
        if "CATKIN_DEVEL_PREFIX" in defines else base / "devel"
    say(f"Devel space: {devel}")
    _check_tool(devel, "catkin_make", args.override_build_tool_check)
    install = Path(defines.pop("CMAKE_INSTALL_PREFIX", str(base / "install")))
    say(f"Install space: {install}")
    if "install" in args.targets:
        raise BuildError('The "install" target is not supported by kame yet: use the devel space '
                         "(source devel/setup.bash)")
    _mark(build_path, "catkin_make")
    _mark(devel, "catkin_make")

    packages = find_workspace_packages(source)
    cache = read_cache(build_path)
    for key in CACHED:
        if key in defines:
            cache[key] = defines[key].strip('"')
    if args.only_pkg_with_deps:
        known = {p.name for p in packages}
        unknown = [n for n in args.only_pkg_with_deps if n not in known]
        if len(unknown) == len(args.only_pkg_with_deps):
            raise BuildError(f'Packages "{", ".join(args.only_pkg_with_deps)}" not found in the workspace')
        if unknown:
            print(f'Packages "{", ".join(sorted(unknown))}" not found in the workspace - ignoring them',
                  file=sys.stderr)
        wanted = with_dependencies(packages, args.only_pkg_with_deps)
        say(f"Whitelisted packages: {', '.join(sorted(wanted))}")
        cache["CATKIN_WHITELIST_PACKAGES"] = ";".join(sorted(wanted))
    write_cache(build_path, {k: v for k, v in cache.items() if v})
    whitelist = cmake_list(cache.get("CATKIN_WHITELIST_PACKAGES", ""))
    blacklist = cmake_list(cache.get("CATKIN_BLACKLIST_PACKAGES", ""))
    selected = select(packages, whitelist, blacklist)
    chosen = selected
    if args.pkg:
        names = {p.name for p in chosen}
        unknown = [n for n in args.pkg if n not in names]
        if len(unknown) == len(args.pkg):
            raise BuildError(f'Packages "{", ".join(args.pkg)}" not found in the workspace')
        chosen = [p for p in chosen if p.name in args.pkg]

    if not (base / ".catkin_workspace").exists():
        (base / ".catkin_workspace").write_text(WORKSPACE_MARKER)
    toolchain = find_toolchain(os.environ)
    if isinstance(toolchain, Toolchain):
        linked = link_toplevel(source, toolchain)
        if linked:
            say(linked)
    search = prefixes(os.environ)
    unresolved = {name: deps for name, deps in missing_components(packages, search).items()
                  if name in {p.name for p in selected}}
    if unresolved and isinstance(toolchain, Missing):
        raise BuildError("\n".join(f'Package "{name}" needs {", ".join(deps)}, which neither the workspace, kame nor '
                                   "this system has: CMake would stop at its find_package(catkin REQUIRED "
                                   "COMPONENTS ...)." for name, deps in unresolved.items()))
    in_cmake = cmake_packages(selected) | set(unresolved) if isinstance(toolchain, Toolchain) else set()
    if in_cmake and isinstance(toolchain, Toolchain):
        _build_cpp(toolchain, [p for p in selected if p.name in in_cmake], packages, args, defines, make_args,
                   (source, build_path, devel, install), search, say, color)
    python_only = [p for p in chosen if p.name not in in_cmake]
    failed = _build_python(python_only, len(chosen) - len(python_only), source, build_path, devel, whitelist,
                           blacklist, color, say, bool(in_cmake))
    if isinstance(toolchain, Missing) and any(p.cpp_targets for p in chosen):
        raise BuildError(toolchain.advice(os_release()) + " The Python packages were built; "
                         "source devel/setup.bash to use them.")
    if failed:
        cpp = ", ".join(r.name for r in failed if r.cpp_targets)
        broken = ", ".join(r.name for r in failed if r.errors)
        causes = ([f"Not built (C++): {cpp}."] if cpp else []) + ([f"Failed: {broken}."] if broken else [])
        raise BuildError(" ".join(causes) + " The other packages were built; source devel/setup.bash to use them.")
    return 0


def _build_cpp(toolchain: Toolchain, in_cmake: list[WorkspacePackage], packages: list[WorkspacePackage],
               args: argparse.Namespace, defines: dict[str, str], make_args: list[str],
               spaces: tuple[Path, Path, Path, Path], search: list[Path], say: Callable[[str], None],
               color: bool) -> None:
    """catkin_make's cmake (only when its inputs changed) and make over the C/C++ packages and what
    they need in the workspace; with --pkg, make in those packages' build folders only."""
    source, build_path, devel, install = spaces
    cmake = CMakeBuild(toolchain, source, build_path, devel, install, os.environ, [], say, color,
                       headers=build_path / KAME_PREFIX)
    needed = {d for p in in_cmake for d in p.depends} - {p.name for p in packages}
    KameMessageHeaders(build_path / KAME_PREFIX, toolchain, search).provide(needed)
    cmake_args = [f"-D{k}={v}" for k, v in defines.items() if k not in CACHED]
    paths = [str(p.path.relative_to(source)) for p in in_cmake]
    if inputs_changed(build_path, paths, [*cmake_args, *cmake.header_arguments()]) or args.force_cmake:
        cmake.configure(sorted(p.name for p in in_cmake), cmake_args)
    else:
        cmake.check()
    if not args.pkg:
        cmake.make(make_args, args.targets)
        return
    for package in in_cmake:
        if package.name in args.pkg:
            cmake.make(make_args, args.targets, build_path / package.path.relative_to(source))


def _build_python(chosen: list[WorkspacePackage], done: int, source: Path, build_path: Path, devel: Path,
                  whitelist: list[str], blacklist: list[str], color: bool, say: Callable[[str], None],
                  by_cmake: bool) -> list[PackageResult]:
    """kame's own build of the Python packages (no CMake), with catkin's lines."""
    python = sys.executable
    underlays = underlay_prefixes(os.environ, devel)
    if chosen or not by_cmake:  # (where CMake built every package, only the setup files are kame's)
        say("####")
        say(f'#### Configuring the workspace in "{build_path}" (kame: Python packages, no CMake)')
        say("####")
        say(f"-- Using CATKIN_DEVEL_PREFIX: {devel}")
        for line in configure_lines(os.environ):
            say(line)
        say(f"-- Using PYTHON_EXECUTABLE: {python}")
        if whitelist:
            say(f"-- Using CATKIN_WHITELIST_PACKAGES: {';'.join(whitelist)}")
        if blacklist:
            say(f"-- Using CATKIN_BLACKLIST_PACKAGES: {';'.join(blacklist)}")
        say(f"-- ~~  traversing {len(chosen)} packages in topological order:")
        for package in chosen:
            say(f"-- ~~  - {package.name}")
        say("-- ~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~")
        for package in chosen:
            say(f"-- +++ processing catkin package: '{package.name}'")
            say(f"-- ==> add_subdirectory({package.path.relative_to(source)})")
            interfaces = package.interface_files()
            if interfaces:
                counts = ", ".join(f"{len(v)} {k}" for k, v in interfaces.items())
                say(f"-- {package.name}: {counts} (no generation step: kame imports them from the package)")
        say("-- Configuring done")
        say("-- Generating done")
        say(f"-- Build files have been written to: {build_path}")
        say("####")
        say(f'#### Building in "{build_path}"')
        say("####")

    failed: list[PackageResult] = []
    total = len(chosen) + done

    def progress(index: int, result: PackageResult) -> None:
        percent = (done + index + 1) * 100 // max(total, 1)
        for warning in result.warnings:
            print(f"WARNING: {warning}", file=sys.stderr)
        if result.failed:
            failed.append(result)
            for message in result.failure_messages():
                line = f"kame: {message}"
                print(f"{RED}{line}{RESET}" if color else line, file=sys.stderr, flush=True)
        say(f"[{percent:3d}%] Built target {result.name}" + (" (Python parts only)" if result.failed else ""))

    build(chosen, devel, [source], underlays, python, shell_dir(), progress)
    return failed


def main(argv: Sequence[str] | None = None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    color = "--no-color" not in args
    try:
        return run(args)
    except (BuildError, WorkspaceError, CMakeFailed, MessageHeaderError) as exc:
        message = str(exc)
        print(f"{RED}{message}{RESET}" if color else message, file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":
    sys.exit(main())
