"""rosbridge's and rosapi's topics_glob, services_glob and params_glob: which names a client sees.

A value is a list of shell-style patterns, as a list or as the launch file's text "[/a/*, /b]";
"" or "[*]" (the defaults) mean every name. A name outside the list is neither listed by rosapi
nor reachable through the bridge.
"""

from __future__ import annotations

import fnmatch
from typing import Any


def parse(value: Any) -> tuple[str, ...] | None:
    """The patterns a parameter names; None for "every name"."""
    if value is None:
        return None
    if isinstance(value, (list, tuple)):
        items = [str(v) for v in value]
    else:
        text = str(value).strip()
        if text.startswith("[") and text.endswith("]"):
            text = text[1:-1]
        items = [part.strip().strip("'\"") for part in text.split(",")]
    patterns = tuple(p for p in items if p)
    if not patterns or "*" in patterns:
        return None
    return patterns


def allows(patterns: tuple[str, ...] | None, name: str) -> bool:
    return patterns is None or any(fnmatch.fnmatchcase(name, p) for p in patterns)
