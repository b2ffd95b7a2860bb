"""One build of a workspace: plan the packages, set each up in the devel space, report.

Rules:
- This is kame's own build, of the packages without C/C++ targets (kame/catkin/cmake.py runs
  the real CMake for the others). Where the machine has no C++ toolchain it is given every
  package: one with C/C++ targets is set up as far as it can be (its targets listed in its
  result, its scripts, setup.py and messages working), and the other packages go on building.
- Messages, services and actions need no generation step (kame's import hook reads them
  from ROS_PACKAGE_PATH); the result counts them.
- dynamic_reconfigure .cfg files are run as catkin runs them and write catkin's files; a
  .cfg that fails is an error of its package, as it fails catkin's build.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

from kame.catkin.devel import Devel
from kame.catkin.workspace import (
    CppTarget,
    WorkspacePackage,
    install_python_programs,
)
from kame.reconfigure.importer import evaluate_cfg


@dataclass
class PackageResult:
    name: str
    cpp_targets: list[CppTarget] = field(default_factory=list)
    python_modules: list[str] = field(default_factory=list)
    scripts: list[str] = field(default_factory=list)
    interfaces: dict[str, list[str]] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)

    @property
    def failed(self) -> bool:
        return bool(self.cpp_targets or self.errors)

    def failure_messages(self) -> list[str]:
        return [*self.errors, *([self.cpp_message()] if self.cpp_targets else [])]

    def cpp_message(self) -> str:
        names = ", ".join(t.name for t in self.cpp_targets)
        return (f"package '{self.name}' needs a C++ build (targets: {names}), which needs the system's CMake, "
                f"C++ compiler, catkin and roscpp; these targets were not built (its Python scripts and messages "
                f"are set up)")


def underlay_prefixes(env: Mapping[str, str], devel: Path) -> list[str]:
    """The prefixes this workspace is built on, as catkin records them for its setup files: every
    CMAKE_PREFIX_PATH entry (catkin workspaces and other prefixes) but the devel space itself,
    underlays first."""
    found = []
    for prefix in env.get("CMAKE_PREFIX_PATH", "").split(os.pathsep):
        if prefix and Path(prefix).resolve() != devel.resolve() and prefix not in found:
            found.append(prefix)
    return list(reversed(found))


def configure_lines(env: Mapping[str, str]) -> list[str]:
    """catkin's all.cmake lines on the prefixes: CMAKE_PREFIX_PATH as a CMake list, then the catkin
    workspaces (prefixes with a .catkin marker) in it, once each, when there are any."""
    value = env.get("CMAKE_PREFIX_PATH", "")
    lines = [f"-- Using CMAKE_PREFIX_PATH: {value.replace(os.pathsep, ';')}"]
    workspaces: list[str] = []
    for prefix in value.split(os.pathsep):
        if prefix and Path(prefix, ".catkin").is_file() and prefix not in workspaces:
            workspaces.append(prefix)
    if workspaces:
        lines.append(f"-- This workspace overlays: {';'.join(workspaces)}")
    return lines


def build_package(devel: Devel, package: WorkspacePackage, python: str) -> PackageResult:
    result = PackageResult(package.name, cpp_targets=package.cpp_targets, interfaces=package.interface_files())
    devel.package_configs(package.name, package.path, package.version)
    setup = package.python_setup()
    if setup is not None and (package.uses_python_setup or not package.cmake_text):
        result.warnings.extend(setup.warnings)
        result.python_modules = devel.python_package(package.path, setup, python)
        result.scripts += devel.scripts(f"lib/{package.name}", package.path, setup.scripts, python)
    elif package.uses_python_setup:
        result.warnings.append(f"package '{package.name}' calls catkin_python_setup() but has no setup.py")
    by_destination: dict[str, list[str]] = {}
    for script, destination in install_python_programs(package.cmake_text, package.name):
        by_destination.setdefault(destination, []).append(script)
    for destination, scripts in by_destination.items():
        result.scripts += devel.scripts(destination, package.path, scripts, python)
    for cfg in package.reconfigure_options():
        try:
            devel.reconfigure(package.name, evaluate_cfg(cfg))
        except Exception as exc:  # whatever the user's .cfg script raises fails its package
            result.errors.append(f"package '{package.name}': {cfg.name} failed: {type(exc).__name__}: {exc}")
    return result


def build(packages: list[WorkspacePackage], devel_path: Path, sources: list[Path], underlays: list[str],
          python: str, shell_dir: Path, progress: Callable[[int, PackageResult], None]) -> list[PackageResult]:
    """Set every package up in the devel space (in order) and write the setup files."""
    devel = Devel(devel_path)
    devel_path.mkdir(parents=True, exist_ok=True)
    devel.clean_previous()
    devel.setup_files(sources, underlays, python, shell_dir)
    results = []
    for index, package in enumerate(packages):
        result = build_package(devel, package, python)
        results.append(result)
        progress(index, result)
    devel.write_manifest()
    return results
