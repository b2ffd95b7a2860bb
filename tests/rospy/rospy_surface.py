"""Lists the public names of Debian's rospy modules (rospy, rospy/*, rospy/impl/*) that kame's
rospy lacks. `python rospy_surface.py list` (under Debian's /usr/bin/python3) prints
{module: [names]}: every name not starting with `_` that is not a module; a module Debian's
interpreter cannot import itself is left out. `python rospy_surface.py missing < listing` (under
kame's) prints the names kame's modules lack, as {module: [names]}."""

import importlib
import json
import pkgutil
import sys
import types


def listing() -> dict:
    import rospy
    import rospy.impl

    found = {}
    for package in (rospy, rospy.impl):
        modules = [package.__name__] + [f"{package.__name__}.{m.name}" for m in pkgutil.iter_modules(package.__path__)]
        for name in modules:
            try:
                module = importlib.import_module(name)
            except Exception:  # e.g. Debian's rospy.impl.udpros, which fails on import
                continue
            found[name] = sorted(n for n, v in vars(module).items()
                                 if not n.startswith("_") and not isinstance(v, types.ModuleType))
    return found


def missing(wanted: dict) -> dict:
    lacking = {}
    for name, public in wanted.items():
        try:
            module = importlib.import_module(name)
        except ImportError:
            lacking[name] = public
            continue
        absent = [n for n in public if not hasattr(module, n)]
        if absent:
            lacking[name] = absent
    return lacking


if __name__ == "__main__":
    if sys.argv[1] == "list":
        print(json.dumps(listing()))
    else:
        print(json.dumps(missing(json.load(sys.stdin))))
