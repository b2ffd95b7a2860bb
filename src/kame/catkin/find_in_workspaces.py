"""catkin's find_in_workspaces: a package's (or a global) folder in the catkin workspaces on
CMAKE_PREFIX_PATH (each with a `.catkin` marker), then /usr, and in their source spaces; what
rosmsg and roslib import from catkin (as catkin_find). File system only.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import Any

__all__ = ["CATKIN_MARKER_FILE", "find_in_workspaces", "get_source_paths", "get_workspaces"]

CATKIN_MARKER_FILE = ".catkin"
_GLOBAL_SEARCH_DIRS = ["bin", "etc", "include", "lib", "share"]
_PROJECT_SEARCH_DIRS = ["etc", "include", "libexec", "share"]


def get_workspaces() -> list[str]:
    """The CMAKE_PREFIX_PATH entries that are catkin workspaces, then /usr (Debian's catkin)."""
    paths = [path for path in os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep) if path]
    return [path for path in paths if os.path.isfile(os.path.join(path, CATKIN_MARKER_FILE))] + ["/usr"]


def get_source_paths(workspace: str) -> list[str]:
    """The source spaces a workspace's `.catkin` marker names (`;`-separated), each once."""
    if workspace == "/usr":
        return []
    filename = os.path.join(workspace, CATKIN_MARKER_FILE)
    if not os.path.isfile(filename):
        raise ValueError(f'Not a catkin workspace: "{workspace}", missing file {filename}')
    with open(filename) as f:
        data = f.read()
    found: list[str] = []
    real: set[str] = set()
    for path in data.split(";") if data else []:
        if os.path.realpath(path) not in real:
            found.append(path)
            real.add(os.path.realpath(path))
    return found


def _valid_search_dirs(search_dirs: Iterable[str] | None, project: str | None) -> list[str]:
    valid = _GLOBAL_SEARCH_DIRS if project is None else _PROJECT_SEARCH_DIRS
    if not search_dirs:
        return list(valid)
    wanted = list(search_dirs)
    unsupported = set(wanted) - set(_GLOBAL_SEARCH_DIRS) - set(_PROJECT_SEARCH_DIRS)
    if unsupported:
        raise ValueError("Unsupported search folders: " + ", ".join(f'"{d}"' for d in unsupported))
    mismatched = set(wanted) - set(valid)
    if mismatched:
        without = "without" if project is None else "for"
        raise ValueError(f"Searching {without} a project can not be combined with the search folders:"
                         + ", ".join(f'"{d}"' for d in mismatched))
    return wanted


def find_in_workspaces(search_dirs: Iterable[str] | None = None, project: str | None = None, path: str | None = None,
                       _workspaces: list[str] | None = None, considered_paths: list[str] | None = None,
                       first_matching_workspace_only: bool = False, first_match_only: bool = False,
                       workspace_to_source_spaces: dict[str, list[str]] | None = None,
                       source_path_to_packages: dict[str, Any] | None = None) -> list[str]:
    """The existing `workspace/<search dir>[/project][/path]` (and, for `share` of a project, its
    folder in the workspace's source spaces), workspaces in order; `considered_paths` gets every
    candidate; ValueError for a search folder catkin does not know."""
    from catkin_pkg.packages import find_packages

    dirs = _valid_search_dirs(search_dirs, project)
    if "libexec" in dirs:
        dirs.insert(dirs.index("libexec"), "lib")
    workspaces = get_workspaces() if _workspaces is None else _workspaces
    to_sources = {} if workspace_to_source_spaces is None else workspace_to_source_spaces
    to_packages = {} if source_path_to_packages is None else source_path_to_packages
    candidates: list[str] = []
    existing: list[str] = []

    def consider(candidate: str) -> bool:
        """Note a candidate; whether the search is over (the first match was asked for)."""
        candidates.append(candidate)
        if os.path.exists(candidate):
            existing.append(candidate)
            return first_match_only
        return False

    done = False
    for workspace in workspaces:
        for sub in dirs:
            candidate = os.path.join(workspace, sub)
            if candidate == "/usr/etc":
                candidate = "/etc"
            candidate = os.path.join(candidate, project) if project else candidate
            candidate = os.path.join(candidate, path) if path else candidate
            if consider(candidate):
                done = True
                break
            if project is None or sub != "share":
                continue
            if workspace not in to_sources:
                to_sources[workspace] = get_source_paths(workspace)
            for source_path in to_sources[workspace]:
                if source_path not in to_packages:
                    to_packages[source_path] = find_packages(source_path)
                matching = [rel for rel, pkg in to_packages[source_path].items() if pkg.name == project]
                if matching:
                    found = source_path if matching[0] == os.curdir else os.path.join(source_path, matching[0])
                    if consider(os.path.join(found, path) if path is not None else found):
                        done = True
                        break
            if done:
                break
        if done or (first_matching_workspace_only and existing):
            break
    if considered_paths is not None:
        considered_paths.extend(candidates)
    return existing
