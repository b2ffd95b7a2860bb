"""rospack: find ROS packages and their dependencies, printing what the real (C++) rospack prints.

    rospack <command> [options] [package]

Packages are found on ROS_PACKAGE_PATH, then among the packages kame ships (kame.msg.catalog);
package.xml is read with catkin_pkg (kame.manifest); dependencies follow rospack's rules
(kame.depgraph). Errors are `[rospack] Error: ...` on stderr (none with -q), exit 1. When the
package is omitted, the current folder is used if it holds a package.xml, by its folder name.
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from kame.depgraph import DependencyError, DependencyGraph
from kame.manifest import ManifestError
from kame.msg.catalog import Package, crawl, find_packages, package_path_roots

USAGE = """USAGE: rospack <command> [options] [package]
  Allowed commands:
    help
    cflags-only-I     [--deps-only] [package]
    cflags-only-other [--deps-only] [package]
    depends           [package] (alias: deps)
    depends-indent    [package] (alias: deps-indent)
    depends-manifests [package] (alias: deps-manifests)
    depends-msgsrv    [package] (alias: deps-msgsrv)
    depends-on        [package]
    depends-on1       [package]
    depends-why --target=<target> [package] (alias: deps-why)
    depends1          [package] (alias: deps1)
    export [--deps-only] --lang=<lang> --attrib=<attrib> [package]
    find [package]
    langs
    libs-only-L     [--deps-only] [package]
    libs-only-l     [--deps-only] [package]
    libs-only-other [--deps-only] [package]
    list
    list-duplicates
    list-names
    plugins --attrib=<attrib> [--top=<toppkg>] [package]
    profile [--length=<length>] [--zombie-only]
    rosdep  [package] (alias: rosdeps)
    rosdep0 [package] (alias: rosdeps0)
    vcs  [package]
    vcs0 [package]
  Extra options:
    -q     Quiets error reports.

 If [package] is omitted, the current working directory
 is used (if it contains a package.xml or manifest.xml).
"""

COMMAND_HELP = {
    "help": ("[command]", "Print help message."),
    "find": ("", "Print absolute path to the package"),
    "list": ("", "Print newline-separated list <package-name> <package-dir> for all packages."),
    "list-names": ("", "Print newline-separated list of packages names for all packages."),
    "list-duplicates": ("", "Print newline-separated list of names of packages that are found more than once "
                            "during the search."),
    "depends": ("[package]", "Print newline-separated, ordered list of all dependencies of the package."),
    "depends1": ("[package]", "Print newline-separated, ordered list of immediate dependencies of the package."),
    "depends-indent": ("[package]", "Print newline-separated, indented list of the entire dependency chain "
                                    "for the package."),
    "depends-on": ("[package]", "Print newline-separated list of all packages that depend on the package. "),
    "depends-on1": ("[package]", "Print newline-separated list of all packages that directly depend on the package."),
    "profile": ("[--length=<length>] [--zombie-only]",
                "Force a full crawl of package directories and report the directories that took the longest "
                "time to crawl.\n\n--length=N how many directories to display\n\n--zombie-only Only print "
                "directories that do not have any manifests."),
}
ALIASES = {"deps": "depends", "deps1": "depends1", "deps-indent": "depends-indent",
           "deps-manifests": "depends-manifests"}
NO_PACKAGE = {"list", "list-names", "list-duplicates", "profile", "help"}
VALUE_OPTIONS = ("--length", "--target", "--lang", "--attrib", "--top")
FLAG_OPTIONS = ("-q", "--deps-only", "--zombie-only")


class RospackError(Exception):
    """Printed as `[rospack] Error: <text>` unless -q; exit 1."""


@dataclass
class Options:
    command: str = ""
    package: str = ""
    quiet: bool = False
    zombie_only: bool = False
    length: int | None = None
    values: dict[str, str] = field(default_factory=dict)


def parse_args(argv: Sequence[str]) -> Options:
    opts = Options()
    positional: list[str] = []
    args = list(argv)
    i = 0
    while i < len(args):
        arg = args[i]
        i += 1
        if arg.startswith("-") and len(arg) > 1:
            name, eq, value = arg.partition("=")
            if name in FLAG_OPTIONS and not eq:
                opts.quiet |= name == "-q"
                opts.zombie_only |= name == "--zombie-only"
            elif name in VALUE_OPTIONS:
                if not eq:
                    if i >= len(args):
                        raise RospackError(f"failed to parse command-line options: the required argument for "
                                           f"option '{name}' is missing")
                    value = args[i]
                    i += 1
                opts.values[name] = value
            elif arg == "-h":
                positional.insert(0, "help")
            elif arg == "--help":
                pass  # rospack accepts it and then finds no command
            else:
                raise RospackError(f"failed to parse command-line options: unrecognised option '{arg}'")
        else:
            positional.append(arg)
    if len(positional) > 2:
        raise RospackError("failed to parse command-line options: too many positional options have been "
                           "specified on the command line")
    if positional:
        opts.command = positional[0]
    if len(positional) > 1:
        opts.package = positional[1]
    if "--length" in opts.values:
        digits = ""
        for ch in opts.values["--length"].strip():
            if not ch.isdigit():
                break
            digits += ch
        opts.length = int(digits or "0")  # rospack reads it with atoi
    return opts


def _packages() -> dict[str, Package]:
    return find_packages(package_path_roots())


def _graph() -> DependencyGraph:
    return DependencyGraph({name: pkg.path for name, pkg in _packages().items()})


def _abs(path: Path) -> str:
    return os.path.abspath(path)


def _package_arg(opts: Options) -> str:
    if opts.package:
        return opts.package
    cwd = Path.cwd()
    if (cwd / "package.xml").is_file() or (cwd / "manifest.xml").is_file():
        return cwd.name
    raise RospackError("no package given")


def cmd_help(opts: Options) -> list[str]:
    if not opts.package:
        return [*USAGE.splitlines(), ""]
    command = ALIASES.get(opts.package, opts.package)
    usage, text = COMMAND_HELP.get(command, ("", ""))
    lines = [f"Usage: rospack {opts.package}{usage}"]
    if text:
        lines += ["", *text.split("\n")]
    return lines


def cmd_find(opts: Options) -> list[str]:
    name = _package_arg(opts)
    pkg = _packages().get(name)
    if pkg is None:
        raise RospackError(f"package '{name}' not found")
    return [_abs(pkg.path)]


def cmd_list(opts: Options) -> list[str]:
    return [f"{name} {_abs(pkg.path)}" for name, pkg in sorted(_packages().items())]


def cmd_list_names(opts: Options) -> list[str]:
    return sorted(_packages())


def cmd_list_duplicates(opts: Options) -> list[str]:
    seen: dict[str, list[Path]] = {}
    for root in package_path_roots():
        for step in crawl(root):
            if step.package is not None:
                seen.setdefault(step.package.name, []).append(step.path)
    lines: list[str] = []
    for name, paths in sorted(seen.items()):
        if len(paths) > 1:
            lines += [name, *(f"- {_abs(p)}" for p in paths)]
    return lines


def cmd_depends1(opts: Options) -> list[str]:
    return _graph().direct(_package_arg(opts))


def cmd_depends(opts: Options) -> list[str]:
    return _graph().closure(_package_arg(opts))


def cmd_depends_indent(opts: Options) -> list[str]:
    return _graph().indented(_package_arg(opts))


def cmd_depends_manifests(opts: Options) -> list[str]:
    graph = _graph()
    paths = [_abs(graph.manifest(dep).path / "package.xml") for dep in graph.closure(_package_arg(opts))]
    return [" ".join(paths)]


def cmd_depends_on(opts: Options) -> list[str]:
    return _graph().dependents(_package_arg(opts), direct=False)


def cmd_depends_on1(opts: Options) -> list[str]:
    return _graph().dependents(_package_arg(opts), direct=True)


@dataclass(frozen=True)
class _Timed:
    seconds: float
    path: Path
    zombie: bool


def cmd_profile(opts: Options) -> list[str]:
    started = time.perf_counter()
    timed: list[_Timed] = []
    for root in package_path_roots():
        entered: list[float] = []
        for step in crawl(root):
            if step.kind == "enter":
                entered.append(time.perf_counter())
            elif step.kind == "leave":
                timed.append(_Timed(time.perf_counter() - entered.pop(), step.path, not step.found_any))
    total = time.perf_counter() - started
    timed.sort(key=lambda t: t.seconds, reverse=True)
    if opts.zombie_only:
        zombies = [str(t.path) for t in timed if t.zombie]
        return zombies if opts.length is None else zombies[: opts.length]
    length = 20 if opts.length is None else opts.length
    lines = [
        f"Full tree crawl took {total:.6f} seconds.",
        "Directories marked with (*) contain no manifest.  You may",
        "want to delete these directories.",
        "To get just of list of directories without manifests,",
        "re-run the profile with --zombie-only",
        "-------------------------------------------------------------",
    ]
    lines += [f"{t.seconds:.6f} {'*' if t.zombie else ' '} {t.path}" for t in timed[:length]]
    return lines


COMMANDS: dict[str, Callable[[Options], list[str]]] = {
    "help": cmd_help,
    "find": cmd_find,
    "list": cmd_list,
    "list-names": cmd_list_names,
    "list-duplicates": cmd_list_duplicates,
    "depends": cmd_depends,
    "depends1": cmd_depends1,
    "depends-indent": cmd_depends_indent,
    "depends-manifests": cmd_depends_manifests,
    "depends-on": cmd_depends_on,
    "depends-on1": cmd_depends_on1,
    "profile": cmd_profile,
}


def run(argv: Sequence[str]) -> int:
    quiet = "-q" in argv
    try:
        opts = parse_args(argv)
        if not opts.command:
            raise RospackError("no command given.  Try 'rospack help'")
        command = ALIASES.get(opts.command, opts.command)
        handler = COMMANDS.get(command)
        if handler is None:
            raise RospackError(f"command {opts.command} not implemented")
        if command in NO_PACKAGE and command != "help" and opts.package:
            raise RospackError("invalid option(s) given")
        lines = handler(opts)
    except (RospackError, DependencyError, ManifestError) as exc:
        if not quiet:
            print(f"[rospack] Error: {exc}", file=sys.stderr)
        # rospack exits 0 when simply no command was given
        return 0 if str(exc).startswith("no command given") else 1
    for line in lines:
        print(line)
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    try:
        status = run(sys.argv[1:] if argv is None else argv)
        sys.stdout.flush()
    except BrokenPipeError:
        sys.stderr.close()
        return 0
    except KeyboardInterrupt:
        return 130
    return status


if __name__ == "__main__":
    sys.exit(main())
