"""Public names of Debian's modules that kame's lack: `python scripts/missing-names.py genpy genmsg`.

Each package's modules (the package and its public submodules) are listed by Debian's
/usr/bin/python3 and by this interpreter; what Debian's module has and kame's does not is printed,
one module a line. Imported modules (os, yaml), __future__ features and stdlib or third-party
classes and functions a module merely imports (StringIO) are not its API and are left out.
Exit status 1 when anything is missing.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

SYSTEM_PYTHON = "/usr/bin/python3"

LISTER = r'''
import __future__, importlib, inspect, json, pkgutil, sys, types
THIRD_PARTY = ("yaml", "numpy", "em")

def public(module, package):
    names = []
    for name, value in vars(module).items():
        if name.startswith("_") or isinstance(value, __future__._Feature):
            continue
        if isinstance(value, types.ModuleType) and not value.__name__.startswith(package + "."):
            continue
        owner = (getattr(value, "__module__", None) or "").split(".")[0]
        if (inspect.isclass(value) or inspect.isroutine(value)) and (
                owner in sys.stdlib_module_names or owner in THIRD_PARTY):
            continue
        names.append(name)
    return sorted(names)

out = {}
for package in sys.argv[1:]:
    top = importlib.import_module(package)
    modules = [package] + [package + "." + m.name for m in pkgutil.iter_modules(top.__path__)
                           if not m.name.startswith("_")]
    for name in modules:
        try:
            out[name] = public(importlib.import_module(name), package)
        except Exception as exc:
            out[name] = "cannot import: %r" % (exc,)
print(json.dumps(out))
'''


def listing(python: str, packages: list[str]) -> dict[str, list[str] | str]:
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    done = subprocess.run([python, "-c", LISTER, *packages], capture_output=True, text=True, env=env, timeout=120,
                          cwd=Path("/"), check=True)
    answer: dict[str, list[str] | str] = json.loads(done.stdout)
    return answer


def missing(packages: list[str]) -> dict[str, list[str]]:
    """Debian's module -> the names kame's lacks (all of them when kame has no such module)."""
    theirs, ours = listing(SYSTEM_PYTHON, packages), listing(sys.executable, packages)
    found: dict[str, list[str]] = {}
    for module, names in theirs.items():
        if isinstance(names, str):
            continue  # Debian's own module does not import here: nothing to compare
        have = ours.get(module, [])
        lacking = list(names) if isinstance(have, str) else [n for n in names if n not in have]
        if lacking:
            found[module] = lacking
    return found


def main(argv: list[str]) -> int:
    found = missing(argv or ["genpy", "genmsg"])
    for module, names in found.items():
        print(f"{module}: {' '.join(names)}")
    return 1 if found else 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
