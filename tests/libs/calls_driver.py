"""Calls module functions named in a JSON request and prints their results (repr) or the
exception type each raised. Run by kame's interpreter and by Debian's /usr/bin/python3 so the
real ROS 1 modules' answers can be compared with kame's."""

from __future__ import annotations

import importlib
import json
import sys
from typing import Any


def call(module: str, function: str, args: list[Any]) -> str:
    target = getattr(importlib.import_module(module), function)
    try:
        result = target(*[bytes.fromhex(a[4:]) if isinstance(a, str) and a.startswith("hex:") else a for a in args])
    except Exception as exc:  # the answer is which exception, compared with upstream's
        return "raises " + type(exc).__name__
    if isinstance(result, (set, frozenset)):
        result = sorted(result)
    return repr(result)


def run(request: list[list[Any]]) -> list[str]:
    return [call(module, function, args) for module, function, args in request]


if __name__ == "__main__":
    print(json.dumps(run(json.load(sys.stdin))))
