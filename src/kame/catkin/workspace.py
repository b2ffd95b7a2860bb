"""A catkin workspace's source space as kame builds it: packages, their order, what each needs.

Rules:
- Packages are found as catkin finds them (catkin_pkg: folders with package.xml, not below
  a CATKIN_IGNORE, not inside another workspace's build/devel), ordered topologically by
  their build, buildtool and run dependencies inside the workspace.
- CATKIN_WHITELIST_PACKAGES keeps only the named packages (when not empty);
  CATKIN_BLACKLIST_PACKAGES drops the named ones.
- kame builds Python packages: scripts, setup.py (catkin_python_setup), msg/srv/action.
  A CMakeLists.txt that compiles C or C++ (add_executable / add_library with C/C++ source
  files) is reported with its target names; its package's Python parts are still set up.
- A package whose find_package(catkin REQUIRED COMPONENTS ...) names a package that neither
  the workspace, kame nor the system has goes to CMake, which fails as catkin fails.
- setup.py is read, not run: the keywords packages, package_dir, py_modules and scripts of
  the setup()/generate_distutils_setup() call, when they are literals (the catkin
  convention). Anything else is reported as a warning.
"""

from __future__ import annotations

import ast
import os
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

CPP_SUFFIXES = (".c", ".cc", ".cpp", ".cxx", ".c++", ".C", ".cu", ".m", ".mm")
_TARGET_CALL = re.compile(r"\b(?:cuda_)?add_(executable|library)\s*\(", re.IGNORECASE)
_BRACKET_COMMENT = re.compile(r"#\[(=*)\[.*?\]\1\]", re.DOTALL)
_LINE_COMMENT = re.compile(r"#[^\n]*")
_FIND_CATKIN = re.compile(r"\bfind_package\s*\(\s*catkin\b", re.IGNORECASE)
_RECONFIGURE_CALL = re.compile(r"\bgenerate_dynamic_reconfigure_options\s*\(", re.IGNORECASE)
_FIND_KEYWORDS = {"OPTIONAL_COMPONENTS", "REQUIRED", "QUIET", "CONFIG", "NO_MODULE", "EXACT", "NO_POLICY_SCOPE"}
_TARGET_KEYWORDS = {"STATIC", "SHARED", "MODULE", "OBJECT", "WIN32", "MACOSX_BUNDLE", "EXCLUDE_FROM_ALL"}


class WorkspaceError(Exception):
    """A workspace that cannot be built (the message says why)."""


@dataclass(frozen=True)
class CppTarget:
    kind: str  # "executable" or "library"
    name: str
    sources: tuple[str, ...]


@dataclass
class PythonSetup:
    """What a package's setup.py declares (paths relative to the package folder)."""

    packages: list[str] = field(default_factory=list)
    package_dir: dict[str, str] = field(default_factory=dict)
    py_modules: list[str] = field(default_factory=list)
    scripts: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    def package_source(self, package: str) -> str:
        """The folder (relative to the package) holding a Python package's files."""
        if package in self.package_dir:
            return self.package_dir[package]
        parts = package.split(".")
        for n in range(len(parts) - 1, 0, -1):
            parent = ".".join(parts[:n])
            if parent in self.package_dir:
                return os.path.join(self.package_dir[parent], *parts[n:])
        return os.path.join(self.package_dir.get("", ""), *parts)


@dataclass
class WorkspacePackage:
    name: str
    path: Path
    depends: set[str]
    cmake_text: str
    version: str = ""

    @property
    def cpp_targets(self) -> list[CppTarget]:
        return cpp_targets(self.cmake_text, self.name)

    @property
    def uses_python_setup(self) -> bool:
        return bool(re.search(r"^\s*catkin_python_setup\s*\(", strip_cmake_comments(self.cmake_text), re.MULTILINE))

    def python_setup(self) -> PythonSetup | None:
        setup_py = self.path / "setup.py"
        if not setup_py.is_file():
            return None
        return read_setup_py(setup_py)

    def reconfigure_options(self) -> list[Path]:
        """The .cfg files of generate_dynamic_reconfigure_options(), as catkin resolves them."""
        text = strip_cmake_comments(self.cmake_text)
        found = []
        for match in _RECONFIGURE_CALL.finditer(text):
            for arg in _call_arguments(text, match.end()).split():
                found.append(self.path / arg.strip('"').replace("${PROJECT_SOURCE_DIR}", str(self.path)))
        return found

    def interface_files(self) -> dict[str, list[str]]:
        found: dict[str, list[str]] = {}
        for kind in ("msg", "srv", "action"):
            folder = self.path / kind
            if folder.is_dir():
                files = sorted(p.name for p in folder.iterdir() if p.suffix == "." + kind)
                if files:
                    found[kind] = files
        return found


def strip_cmake_comments(text: str) -> str:
    return _LINE_COMMENT.sub("", _BRACKET_COMMENT.sub("", text))


def _call_arguments(text: str, start: int) -> str:
    depth = 1
    i = start
    while i < len(text) and depth:
        if text[i] == "(":
            depth += 1
        elif text[i] == ")":
            depth -= 1
        i += 1
    return text[start : i - 1]


def catkin_components(cmake_text: str) -> list[str]:
    """The packages `find_package(catkin REQUIRED COMPONENTS ...)` asks CMake for."""
    text = strip_cmake_comments(cmake_text)
    found: list[str] = []
    for match in _FIND_CATKIN.finditer(text):
        args = _call_arguments(text, match.end()).split()
        if "COMPONENTS" not in args:
            continue
        for arg in args[args.index("COMPONENTS") + 1 :]:
            if arg in _FIND_KEYWORDS:
                break
            if arg not in found:
                found.append(arg)
    return found


def cpp_targets(cmake_text: str, project: str) -> list[CppTarget]:
    """The targets a CMakeLists.txt compiles from C/C++ sources."""
    text = strip_cmake_comments(cmake_text)
    found = []
    for match in _TARGET_CALL.finditer(text):
        args = _call_arguments(text, match.end()).split()
        if not args:
            continue
        name = args[0].replace("${PROJECT_NAME}", project)
        if any(a in ("IMPORTED", "ALIAS", "INTERFACE") for a in args[1:2]):
            continue
        sources = tuple(a.strip('"') for a in args[1:] if a not in _TARGET_KEYWORDS)
        compiled = [s for s in sources if s.endswith(CPP_SUFFIXES)]
        if compiled or (sources and not any(s.endswith(".py") for s in sources)):
            found.append(CppTarget(match.group(1).lower(), name, sources))
    return found


def _literal(node: ast.AST) -> Any:
    return ast.literal_eval(node)


def read_setup_py(path: Path) -> PythonSetup:
    result = PythonSetup()
    try:
        tree = ast.parse(path.read_text(), str(path))
    except (OSError, SyntaxError, ValueError) as exc:
        result.warnings.append(f"cannot read {path}: {exc}")
        return result
    calls = [n for n in ast.walk(tree) if isinstance(n, ast.Call)]
    keywords: dict[str, ast.AST] = {}
    for call in calls:
        func = call.func
        name = func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""
        if name in ("setup", "generate_distutils_setup"):
            for kw in call.keywords:
                if kw.arg:
                    keywords.setdefault(kw.arg, kw.value)
    for key in ("packages", "package_dir", "py_modules", "scripts"):
        if key not in keywords:
            continue
        try:
            value = _literal(keywords[key])
        except ValueError:
            result.warnings.append(f"{path}: {key}= is not a literal; kame reads setup.py without running it")
            continue
        setattr(result, key, dict(value) if key == "package_dir" else list(value))
    return result


def find_workspace_packages(source: Path) -> list[WorkspacePackage]:
    """Every package below the source space, in dependency order (dependencies first)."""
    from catkin_pkg.packages import find_packages
    from catkin_pkg.topological_order import topological_order_packages

    try:
        found = find_packages(str(source), exclude_subspaces=True)
    except RuntimeError as exc:  # e.g. two packages of one name
        raise WorkspaceError(str(exc)) from None
    except Exception as exc:  # an invalid package.xml
        raise WorkspaceError(f"{exc}") from None
    ordered = topological_order_packages(found)
    result = []
    for relpath, pkg in ordered:
        if relpath is None:  # a cycle: catkin_pkg reports it this way
            raise WorkspaceError(f"circular dependency in the workspace: {pkg}")
        try:
            pkg.evaluate_conditions(os.environ)
        except Exception:
            pass
        depends = {d.name for d in [*pkg.build_depends, *pkg.buildtool_depends, *pkg.exec_depends,
                                    *getattr(pkg, "run_depends", [])]
                   if getattr(d, "evaluated_condition", True) is not False}
        folder = source / relpath
        cmake = folder / "CMakeLists.txt"
        text = cmake.read_text(errors="replace") if cmake.is_file() else ""
        result.append(WorkspacePackage(pkg.name, folder, depends, text, pkg.version))
    return result


def with_dependencies(packages: list[WorkspacePackage], names: list[str]) -> set[str]:
    """`names` plus their dependencies (recursively) inside the workspace."""
    by_name = {p.name: p for p in packages}
    wanted: set[str] = set()
    todo = [n for n in names if n in by_name]
    while todo:
        name = todo.pop()
        if name in wanted:
            continue
        wanted.add(name)
        todo.extend(d for d in by_name[name].depends if d in by_name)
    return wanted


def cmake_packages(packages: list[WorkspacePackage]) -> set[str]:
    """The packages CMake builds: those with C/C++ targets and what they depend on in the workspace."""
    return with_dependencies(packages, [p.name for p in packages if p.cpp_targets])


def unresolved_components(packages: list[WorkspacePackage], known: Callable[[str], bool]) -> dict[str, list[str]]:
    """Per package, the find_package(catkin COMPONENTS ...) names that are not in the workspace
    and that `known` (kame's packages, the system's) does not know either."""
    names = {p.name for p in packages}
    found = {}
    for package in packages:
        missing = [c for c in catkin_components(package.cmake_text) if c not in names and not known(c)]
        if missing:
            found[package.name] = missing
    return found


def select(packages: list[WorkspacePackage], whitelist: list[str], blacklist: list[str]) -> list[WorkspacePackage]:
    return [p for p in packages if (not whitelist or p.name in whitelist) and p.name not in blacklist]


def cmake_list(value: str) -> list[str]:
    """A CMake list value (`a;b`, also `a b` or `a,b` as people type them)."""
    return [v for v in re.split(r"[;,\s]+", value.strip().strip('"')) if v]


_INSTALL_PYTHON = re.compile(r"\bcatkin_install_python\s*\(", re.IGNORECASE)
_DESTINATIONS = {"${CATKIN_PACKAGE_BIN_DESTINATION}": "lib/{package}", "${CATKIN_GLOBAL_BIN_DESTINATION}": "bin"}


def install_python_programs(cmake_text: str, package: str) -> list[tuple[str, str]]:
    """(script, devel-relative destination) of each catkin_install_python(PROGRAMS ...)."""
    text = strip_cmake_comments(cmake_text)
    found = []
    for match in _INSTALL_PYTHON.finditer(text):
        args = [a.strip('"') for a in _call_arguments(text, match.end()).split()]
        if not args or args[0].upper() != "PROGRAMS" or "DESTINATION" not in args:
            continue
        at = args.index("DESTINATION")
        destination = args[at + 1] if at + 1 < len(args) else ""
        relative = _DESTINATIONS.get(destination)
        if relative is None:
            continue
        for script in args[1:at]:
            if script != "OPTIONAL":
                found.append((script, relative.format(package=package)))
    return found
