"""`from my_pkg.cfg import TutorialsConfig` with no build step: the .cfg file is run on import.

my_pkg.cfg is made for a ROS package on ROS_PACKAGE_PATH holding cfg/*.cfg; its module
TutorialsConfig is filled by evaluating cfg/Tutorials.cfg with kame's ParameterGenerator, so
it holds what catkin's generated module holds (config_description, defaults, min, max,
level, type, all_level and the constants). A real Python module of the same name (a
catkin-built devel space) keeps its place.
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import os
import sys
from collections.abc import Sequence
from pathlib import Path
from types import ModuleType

from kame.msg.catalog import Package
from kame.msg.importer import user_packages
from kame.reconfigure.generator import GeneratedConfig, collect_generated, module_names


class CfgError(ImportError):
    """A .cfg file that does not evaluate to exactly one configuration."""


def evaluate_cfg(path: Path) -> GeneratedConfig:
    """Run a .cfg script as catkin would (as __main__, its exit() ending it) and return what it generated."""
    code = compile(path.read_text(encoding="utf-8"), str(path), "exec")
    results: list[GeneratedConfig] = []
    saved_argv = sys.argv
    collect_generated(results)
    try:
        sys.argv = [str(path)]
        exec(code, {"__name__": "__main__", "__file__": str(path), "__builtins__": __builtins__})
    except SystemExit as stop:
        if stop.code not in (None, 0):
            raise CfgError(f"{path} exited with {stop.code!r}") from None
    finally:
        sys.argv = saved_argv
        collect_generated(None)
    if len(results) != 1:
        raise CfgError(f"{path} called generate() {len(results)} times; one call is expected")
    return results[0]


def cfg_file(package: Package, config_module: str) -> Path | None:
    if not config_module.endswith("Config"):
        return None
    path = package.path / "cfg" / (config_module.removesuffix("Config") + ".cfg")
    return path if path.is_file() else None


class _CfgLoader(importlib.abc.Loader):
    def __init__(self, cfg: Path | None) -> None:
        self.cfg = cfg

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType:
        module = ModuleType(spec.name)
        if self.cfg is None:
            module.__path__ = []
        return module

    def exec_module(self, module: ModuleType) -> None:
        if self.cfg is not None:
            module.__file__ = str(self.cfg)
            module.__dict__.update(module_names(evaluate_cfg(self.cfg)))


class CfgFinder(importlib.abc.MetaPathFinder):
    """Finds `pkg.cfg` and `pkg.cfg.<Name>Config` for packages on ROS_PACKAGE_PATH with cfg/*.cfg."""

    def find_spec(
        self, fullname: str, path: Sequence[str] | None, target: ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        parts = fullname.split(".")
        if len(parts) not in (2, 3) or parts[1] != "cfg" or not os.environ.get("ROS_PACKAGE_PATH"):
            return None
        package = user_packages().get(parts[0])
        if package is None or not package.interface_files("cfg"):
            return None
        existing = importlib.machinery.PathFinder.find_spec(fullname, path)
        if existing is not None and existing.loader is not None:
            return None
        if len(parts) == 2:
            return importlib.machinery.ModuleSpec(fullname, _CfgLoader(None), is_package=True)
        cfg = cfg_file(package, parts[2])
        return None if cfg is None else importlib.machinery.ModuleSpec(fullname, _CfgLoader(cfg))
