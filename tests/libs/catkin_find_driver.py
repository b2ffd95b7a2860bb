"""catkin's find_in_workspaces, as rosmsg and roslib.packages import it, on a workspace given on
stdin (CMAKE_PREFIX_PATH names its devel space); prints JSON. Run by kame's interpreter and
Debian's /usr/bin/python3 (catkin's own)."""

from __future__ import annotations

import json
import sys
from typing import Any

import roslib.packages
import rosmsg


def main() -> None:
    root = json.load(sys.stdin)["root"]
    find = rosmsg.find_in_workspaces
    considered: list[str] = []
    cases: list[Any] = [
        find(search_dirs=["share"], project="pkg_src"),
        find(search_dirs=["share"], project="pkg_devel", path="msg"),
        find(project="pkg_src", considered_paths=considered),
        find(search_dirs=["share"], project="pkg_src", first_match_only=True),
        find(search_dirs=["lib"], path="nothing_here"),
        find(project="pkg_devel", first_matching_workspace_only=True),
    ]
    for bad in (["bin"], ["nope"]):
        try:
            find(search_dirs=bad, project="pkg_src")
        except ValueError as exc:
            cases.append(str(exc))
    out = {"cases": cases, "considered": considered, "same": roslib.packages.catkin_find is find}
    sys.stdout.write(json.dumps(out).replace(root, "ROOT"))


if __name__ == "__main__":
    main()
