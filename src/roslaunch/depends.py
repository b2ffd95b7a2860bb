"""roslaunch.depends: the packages a launch file uses (its nodes' and includes' packages) and those
its package.xml does not declare, as `roslaunch-deps` and rostest's roslaunch-check report them.

Rules (roslaunch's depends): <arg>s are followed (command-line `name:=value` first), `if`/`unless`
honoured, <group>s and <include>s entered; an include's package is a dependency of the
including file when it is another package. A package's declared dependencies are its
package.xml's run_depend (and test_depend when asked), read by catkin_pkg as ROS does.
"""

from __future__ import annotations

import os
import re
import sys
from collections.abc import Sequence
from typing import Any
from xml.dom import Node as DomNode
from xml.dom.minidom import parse

import rospkg
from roslaunch.loader import convert_value, load_mappings
from roslaunch.substitution_args import resolve_args

__all__ = ["NAME", "DomNode", "RoslaunchDeps", "RoslaunchDepsException", "calculate_missing", "convert_value",
           "fullusage", "load_mappings", "parse", "parse_launch", "print_deps", "resolve_args", "rl_file_deps",
           "roslaunch_deps", "roslaunch_deps_main"]

NAME = "roslaunch-deps"


class RoslaunchDepsException(Exception):
    """A launch file whose dependencies cannot be worked out."""


class RoslaunchDeps:
    """What one launch file uses: (package, type) of its nodes, its includes, the packages."""

    def __init__(self, nodes: list[tuple[str, str]] | None = None, includes: list[str] | None = None,
                 pkgs: list[str] | None = None) -> None:
        self.nodes = [] if nodes is None else nodes
        self.includes = [] if includes is None else includes
        self.pkgs = [] if pkgs is None else pkgs

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, RoslaunchDeps) and set(self.nodes) == set(other.nodes)
                and set(self.includes) == set(other.includes) and set(self.pkgs) == set(other.pkgs))

    __hash__ = None  # type: ignore[assignment]  # mutable, compared by value, as ROS's

    def __repr__(self) -> str:
        return f"nodes: {self.nodes}\nincludes: {self.includes}\npkgs: {self.pkgs}"

    __str__ = __repr__


def _resolved(text: str, context: dict[str, Any]) -> str:
    return resolve_args(text, context) or ""


def _get_arg_value(tag: Any, context: dict[str, Any]) -> str:
    name = tag.attributes["name"].value
    if "value" in tag.attributes:
        return _resolved(tag.attributes["value"].value, context)
    if name in context["arg"]:
        return str(context["arg"][name])
    if "default" in tag.attributes:
        return _resolved(tag.attributes["default"].value, context)
    raise RoslaunchDepsException(f"No value for arg [{name}]")


def _check_ifunless(tag: Any, context: dict[str, Any]) -> bool:
    if "if" in tag.attributes:
        return bool(convert_value(_resolved(tag.attributes["if"].value, context), "bool"))
    if "unless" in tag.attributes:
        return not convert_value(_resolved(tag.attributes["unless"].value, context), "bool")
    return True


def _elements(tags: Any) -> list[Any]:
    return [t for t in tags if t.nodeType == DomNode.ELEMENT_NODE]


def _parse_subcontext(tags: Any, context: dict[str, Any]) -> dict[str, Any]:
    subcontext: dict[str, Any] = {"arg": {}}
    for tag in _elements(tags or []):
        if tag.tagName == "arg" and _check_ifunless(tag, context):
            subcontext["arg"][tag.attributes["name"].value] = _get_arg_value(tag, context)
    return subcontext


def _package_of(path: str) -> str | None:
    return rospkg.get_package_name(os.path.dirname(os.path.abspath(path)))


def _include(tag: Any, launch_file: str, file_deps: dict[str, RoslaunchDeps], verbose: bool,
             context: dict[str, Any]) -> None:
    try:
        sub_launch_file = _resolved(tag.attributes["file"].value, context)
    except KeyError as exc:
        raise RoslaunchDepsException(f"Cannot load roslaunch <{tag.tagName}> tag: missing required attribute {exc}."
                                     f"\nXML is {tag.toxml()}") from None
    if sub_launch_file == "":
        if verbose:
            print(f"Empty <include> in {launch_file}. Skipping <include> of {tag.attributes['file'].value}")
        return
    if verbose:
        print(f"processing included launch {sub_launch_file}")
    sub_pkg = _package_of(sub_launch_file)
    if sub_pkg is None:
        print(f"ERROR: cannot determine package for [{sub_launch_file}]", file=sys.stderr)
    deps = file_deps[launch_file]
    if sub_launch_file not in deps.includes:
        deps.includes.append(sub_launch_file)
    if _package_of(launch_file) != sub_pkg and sub_pkg is not None:
        deps.pkgs.append(sub_pkg)
    file_deps[sub_launch_file] = RoslaunchDeps()
    try:
        dom = parse(sub_launch_file).getElementsByTagName("launch")
    except OSError:
        raise RoslaunchDepsException(f"Cannot load roslaunch include '{sub_launch_file}' in '{launch_file}'") from None
    if not dom:
        print(f"ERROR: {sub_launch_file} is not a valid roslaunch file", file=sys.stderr)
        return
    sub_context = _parse_subcontext(tag.childNodes, context)
    if "pass_all_args" in tag.attributes:
        sub_context["arg"] = {**context["arg"], **sub_context["arg"]}
    _parse_launch(dom[0].childNodes, sub_launch_file, file_deps, verbose, sub_context)


def _parse_launch(tags: Any, launch_file: str, file_deps: dict[str, RoslaunchDeps], verbose: bool,
                  context: dict[str, Any]) -> None:
    context["filename"] = os.path.abspath(launch_file)
    for tag in _elements(tags):
        if not _check_ifunless(tag, context):
            continue
        if tag.tagName == "group":
            _parse_launch(tag.childNodes, launch_file, file_deps, verbose, context)
        elif tag.tagName == "arg":
            context["arg"][tag.attributes["name"].value] = _get_arg_value(tag, context)
        elif tag.tagName == "include":
            _include(tag, launch_file, file_deps, verbose, context)
        elif tag.tagName in ("node", "test"):
            try:
                pkg, node_type = (_resolved(tag.attributes[a].value, context) for a in ("pkg", "type"))
            except KeyError as exc:
                raise RoslaunchDepsException(f"Cannot load roslaunch <{tag.tagName}> tag: missing required attribute "
                                             f"{exc}.\nXML is {tag.toxml()}") from None
            deps = file_deps[launch_file]
            if (pkg, node_type) not in deps.nodes:
                deps.nodes.append((pkg, node_type))
            if pkg not in deps.pkgs:
                deps.pkgs.append(pkg)


def parse_launch(launch_file: str, file_deps: dict[str, RoslaunchDeps], verbose: bool) -> None:
    """Add `launch_file`'s dependencies (and its includes') to `file_deps`."""
    if verbose:
        print(f"processing launch {launch_file}")
    try:
        dom = parse(launch_file).getElementsByTagName("launch")
    except Exception:
        raise RoslaunchDepsException(f"invalid XML in {launch_file}") from None
    if not dom:
        raise RoslaunchDepsException(f"invalid XML in {launch_file}")
    file_deps[launch_file] = RoslaunchDeps()
    _parse_launch(dom[0].childNodes, launch_file, file_deps, verbose, {"arg": load_mappings(sys.argv)})


def rl_file_deps(file_deps: dict[str, RoslaunchDeps], launch_file: str, verbose: bool = False) -> None:
    parse_launch(launch_file, file_deps, verbose)


def fullusage() -> None:
    print(f"Usage:\n\t{NAME} [options] <file-or-package>\n")


def print_deps(base_pkg: str | None, file_deps: dict[str, RoslaunchDeps], verbose: bool) -> None:
    """The packages used, on one line (verbose: each node and file first)."""
    if verbose:
        for f, deps in file_deps.items():
            for p, t in deps.nodes:
                print(f"{p} [{p}/{t}]")
            pkg = _package_of(f)
            if pkg is None:
                print(f"ERROR: cannot determine package for [{pkg}]", file=sys.stderr)
            else:
                print(f"{pkg} [{f}]")
        print("-" * 80)
    print(" ".join(set(p for deps in file_deps.values() for p in deps.pkgs)))


def _declared(manifest_dir: str, use_test_depends: bool) -> set[str]:
    from catkin_pkg.package import parse_package

    package = parse_package(manifest_dir)
    found = {d.name for d in package.run_depends}
    if use_test_depends:
        found |= {d.name for d in package.test_depends}
    return found


def calculate_missing(base_pkg: str | None, missing: dict[str, set[str]], file_deps: dict[str, RoslaunchDeps],
                      use_test_depends: bool = False) -> dict[str, set[str]]:
    """Add to `missing` the packages each file's package uses but does not declare."""
    rospack = rospkg.RosPack()
    for launch_file in file_deps:
        pkg = _package_of(launch_file)
        if pkg is None:
            print(f"ERROR: cannot determine package for [{pkg}]", file=sys.stderr)
            continue
        declared = _declared(rospack.get_path(pkg), use_test_depends) | {pkg}
        missing.setdefault(pkg, set()).update(set(file_deps[launch_file].pkgs) - declared)
    return missing


def roslaunch_deps(files: Sequence[str], verbose: bool = False, use_test_depends: bool = False,
                   ignore_unset_args: bool = False) -> tuple[str | None, dict[str, RoslaunchDeps], dict[str, set[str]]]:
    """(the files' package, {file: RoslaunchDeps}, {package: undeclared packages}); the files must
    be of one package."""
    file_deps: dict[str, RoslaunchDeps] = {}
    missing: dict[str, set[str]] = {}
    base_pkg = None
    for launch_file in files:
        if not os.path.exists(launch_file):
            raise RoslaunchDepsException(f"roslaunch file [{launch_file}] does not exist")
        pkg = _package_of(launch_file)
        if base_pkg and pkg != base_pkg:
            raise RoslaunchDepsException(f"roslaunch files must be in the same package: {base_pkg} vs. {pkg}")
        base_pkg = pkg
        try:
            rl_file_deps(file_deps, launch_file, verbose)
        except RoslaunchDepsException as exc:
            if not (ignore_unset_args and re.search("No value for arg", str(exc))):
                raise
    calculate_missing(base_pkg, missing, file_deps, use_test_depends=use_test_depends)
    return base_pkg, file_deps, missing


def roslaunch_deps_main(argv: Sequence[str] = sys.argv) -> None:
    """`roslaunch-deps [-v] [-w] FILE...`."""
    from optparse import OptionParser

    parser = OptionParser(usage="usage: %prog [options] <file(s)...>", prog=NAME)
    parser.add_option("--verbose", "-v", action="store_true", dest="verbose", default=False, help="Verbose output")
    parser.add_option("--warn", "-w", action="store_true", dest="warn", default=False,
                      help="Warn about missing manifest dependencies")
    options, args = parser.parse_args(list(argv[1:]))
    if not args:
        parser.error("please specify a launch file")
    files = [arg for arg in args if os.path.exists(arg)]
    packages = [arg for arg in args if not os.path.exists(arg)]
    if packages:
        parser.error(f"cannot locate {','.join(packages)}")
    try:
        base_pkg, file_deps, missing = roslaunch_deps(files, verbose=options.verbose)
    except RoslaunchDepsException as exc:
        print(str(exc), file=sys.stderr)
        sys.exit(1)
    if options.warn:
        print("Dependencies:")
    print_deps(base_pkg, file_deps, options.verbose)
    if options.warn:
        print("\nMissing declarations:")
        for pkg, miss in missing.items():
            if miss:
                print(f"{pkg}/manifest.xml:")
                for m in miss:
                    print(f'  <depend package="{m}" />')
