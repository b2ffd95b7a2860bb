"""genmsg.command_line: the generators' -I options as a search path."""

from __future__ import annotations

from collections.abc import Iterable

__all__ = ["includepath_to_dict"]


def includepath_to_dict(includepath: Iterable[str] | None) -> dict[str, list[str]]:
    """['std_msgs:/path/msg', ...] -> {'std_msgs': ['/path/msg', ...]} (empty paths left out;
    an entry without ':' is split as genmsg splits it, at its last character)."""
    search_path: dict[str, list[str]] = {}
    for path in includepath or ():
        colon = path.find(":")
        key, value = path[:colon], path[colon + 1:]
        if value:
            search_path.setdefault(key, []).append(value)
    return search_path
