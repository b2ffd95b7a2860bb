"""Lists the public names of each of roslaunch's modules, as JSON: run under Debian's interpreter
it lists ROS's, under kame's kame's. `python roslaunch_surface.py --missing` (under kame's
interpreter) prints, per module, the names Debian's roslaunch has and kame's lacks.

Public: not starting with `_`, not a module, not a `from __future__` feature (a compiler
directive such as print_function, not a name a program uses).
"""

from __future__ import annotations
import __future__

import importlib
import json
import os
import pkgutil
import subprocess
import sys
import types
from typing import Any

SYSTEM_PYTHON = "/usr/bin/python3"


def surface() -> dict[str, Any]:
    """{module: [public names]}, or {module: "import error: ..."}."""
    import roslaunch

    found: dict[str, Any] = {}
    for name in ["roslaunch", *sorted(f"roslaunch.{m.name}" for m in pkgutil.iter_modules(roslaunch.__path__))]:
        try:
            module = importlib.import_module(name)
        except Exception as exc:  # a module that does not import is reported, not fatal to the listing
            found[name] = f"import error: {exc!r}"
            continue
        found[name] = sorted(n for n, v in vars(module).items() if not n.startswith("_")
                             and not isinstance(v, (types.ModuleType, __future__._Feature)))
    return found


def missing(debian: dict[str, Any], kame: dict[str, Any]) -> dict[str, list[str]]:
    """{module: names Debian's has and kame's lacks}, for the modules where any are lacking."""
    gaps = {}
    for module, names in debian.items():
        ours = kame.get(module)
        lacking = list(names) if not isinstance(ours, list) else [n for n in names if n not in ours]
        if lacking:
            gaps[module] = lacking
    return gaps


def debian_surface() -> dict[str, Any]:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    done = subprocess.run([SYSTEM_PYTHON, __file__], capture_output=True, text=True, env=env, timeout=120,
                          check=True)
    answer: dict[str, Any] = json.loads(done.stdout)
    return answer


if __name__ == "__main__":
    if sys.argv[1:] == ["--missing"]:
        print(json.dumps(missing(debian_surface(), surface()), indent=1))
    else:
        print(json.dumps(surface()))
