#!/usr/bin/env python3
"""Which public names of ROS 1's Python modules kame lacks.

Run by hand with kame's interpreter: `.venv/bin/python scripts/module-surface.py [PKG ...]`
prints one line per missing name (`module.name`, or `module` when kame has no such module).
It asks Debian's /usr/bin/python3 to import every module Debian ships under
/usr/lib/python3/dist-packages/<pkg>/ and list its public names (no leading underscore, not an
imported module, not a `from __future__` feature), then looks each up in kame's module of the
same name.
`--list-names PKG ...` is the half Debian's interpreter runs: that listing as JSON.
tests/test_module_surface.py holds the answer to README's "ROS Python modules: names not provided".
"""

from __future__ import annotations
import __future__

import argparse
import importlib
import inspect
import json
import os
import subprocess
import sys
import warnings
from pathlib import Path

DEBIAN_PYTHON = "/usr/bin/python3"
DIST_PACKAGES = Path("/usr/lib/python3/dist-packages")
PACKAGES = ("roslaunch", "rospy", "genpy", "genmsg", "rosbag", "roslib", "rosgraph", "rostopic", "rosservice",
            "rosnode", "rosparam", "rosmsg")


def module_names(package: str, root: Path = DIST_PACKAGES) -> list[str]:
    """The dotted names of the modules in `root/package`, the package first."""
    names = []
    for path in sorted((root / package).rglob("*.py")):
        parts = list(path.relative_to(root).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        names.append(".".join(parts))
    return sorted(names, key=lambda name: (name.count("."), name))


def public_names(module: object) -> list[str]:
    return sorted(name for name, value in vars(module).items()
                  if not name.startswith("_") and not inspect.ismodule(value)
                  and not isinstance(value, __future__._Feature))


def _import(name: str) -> object:
    with warnings.catch_warnings():  # deprecated modules (roslib.rosenv, ...) are imported on purpose
        warnings.simplefilter("ignore")
        return importlib.import_module(name)


def list_names(packages: list[str]) -> dict[str, list[str] | None]:
    """Each module's public names; None for a module that does not import here."""
    listing: dict[str, list[str] | None] = {}
    for package in packages:
        for name in module_names(package):
            try:
                listing[name] = public_names(_import(name))
            except Exception:  # a module whose import needs what this machine lacks is skipped, not fatal
                listing[name] = None
    return listing


def debian_listing(packages: list[str]) -> dict[str, list[str] | None]:
    env = {key: value for key, value in os.environ.items() if key not in ("PYTHONPATH", "VIRTUAL_ENV")}
    done = subprocess.run([DEBIAN_PYTHON, "-s", os.path.abspath(__file__), "--list-names", *packages],
                          capture_output=True, text=True, env=env, cwd="/", timeout=300, check=True)
    listing: dict[str, list[str] | None] = json.loads(done.stdout)
    return listing


def debian_has(package: str) -> bool:
    return os.path.exists(DEBIAN_PYTHON) and (DIST_PACKAGES / package / "__init__.py").exists()


def missing(listing: dict[str, list[str] | None]) -> list[str]:
    """What kame lacks of `listing`: `module` for a module it does not have, and `module.name` for
    each public name that module (kame's, or none) does not define."""
    lacking = []
    for module_name, names in listing.items():
        if names is None:
            continue
        try:
            module: object | None = _import(module_name)
        except ImportError:
            module = None
            lacking.append(module_name)
        lacking.extend(f"{module_name}.{name}" for name in names if module is None or not hasattr(module, name))
    return lacking


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("packages", nargs="*", default=list(PACKAGES))
    parser.add_argument("--list-names", action="store_true", help="print this interpreter's listing as JSON")
    args = parser.parse_args()
    if args.list_names:
        json.dump(list_names(args.packages), sys.stdout)
        return
    for line in missing(debian_listing([p for p in args.packages if debian_has(p)])):
        print(line)


if __name__ == "__main__":
    main()
