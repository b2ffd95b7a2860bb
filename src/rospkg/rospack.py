"""rospkg.rospack: RosPack and RosStack, the packages and stacks on the ROS paths.

Packages are found as rospkg crawls (kame.catkin's rules for rospack are those of the C++
tool): each path entry is walked, the first path holding a name wins, a folder with a
package.xml is a leaf, CATKIN_IGNORE and rospack_nosubdirs stop the descent, hidden folders are
skipped. RosPack lists the packages that are not metapackages, RosStack the metapackages (and
rosbuild stacks, folders with a stack.xml).
"""

from __future__ import annotations

import builtins
import os
import threading
import xml.etree.ElementTree as ElementTree
from collections.abc import Sequence
from typing import Any, ClassVar

from .common import MANIFEST_FILE, PACKAGE_FILE, STACK_FILE, ResourceNotFound
from .environment import get_ros_paths
from .manifest import InvalidManifest, Manifest, parse_manifest_file

__all__ = ["ManifestManager", "RosPack", "RosStack", "expand_to_packages", "get_package_name", "list_by_path"]

_cache_lock = threading.Lock()


def _package_xml_name(path: str) -> tuple[str, bool] | None:
    """(name, is_metapackage) of a package.xml, or None when it cannot be read."""
    try:
        root = ElementTree.parse(path).getroot()
    except (ElementTree.ParseError, OSError):
        return None
    name = (root.findtext("name") or "").strip(" \n\r\t")
    return (name, root.find("./export/metapackage") is not None) if name else None


def list_by_path(manifest_name: str, path: str, cache: dict[str, str] | None) -> list[str]:
    """The resources of kind `manifest_name` under `path`, recorded in `cache` (name -> folder)."""
    resources: list[str] = []
    for folder, dirs, files in os.walk(os.path.abspath(path), topdown=True, followlinks=True):
        dirs.sort()
        if "CATKIN_IGNORE" in files:
            dirs.clear()
            continue
        if PACKAGE_FILE in files:
            found = _package_xml_name(os.path.join(folder, PACKAGE_FILE))
            if found is not None:
                name, is_metapackage = found
                if manifest_name == PACKAGE_FILE or is_metapackage == (manifest_name == STACK_FILE):
                    if name not in resources:
                        resources.append(name)
                        if cache is not None:
                            cache[name] = folder
                    dirs.clear()
                    continue
        if manifest_name in files:
            name = os.path.basename(folder)
            if name not in resources:
                resources.append(name)
                if cache is not None:
                    cache[name] = folder
            dirs.clear()
        elif MANIFEST_FILE in files or PACKAGE_FILE in files or "rospack_nosubdirs" in files:
            dirs.clear()
        else:
            dirs[:] = [d for d in dirs if not d.startswith(".")]
    return resources


class ManifestManager:
    """Finds resources of one kind on the ROS paths; caches what it found and read."""

    _instances: ClassVar[dict[str, Any]]

    def __init__(self, manifest_name: str, ros_paths: Sequence[str] | None = None) -> None:
        self._manifest_name = manifest_name
        self._ros_paths = list(get_ros_paths() if ros_paths is None else ros_paths)
        self._manifests: dict[str, Manifest] = {}
        self._depends_cache: dict[str, builtins.list[str]] = {}
        self._location_cache: dict[str, str] | None = None
        self._custom_cache: dict[str, Any] = {}

    @classmethod
    def get_instance(cls, ros_paths: Sequence[str] | None = None) -> Any:
        """One shared instance per set of ROS paths."""
        if "_instances" not in cls.__dict__:
            cls._instances = {}
        key = str(tuple(get_ros_paths() if ros_paths is None else ros_paths))
        if key not in cls._instances:
            cls._instances[key] = cls(ros_paths)  # type: ignore[arg-type]  # subclasses take ros_paths only
        return cls._instances[key]

    def get_ros_paths(self) -> builtins.list[str]:
        return self._ros_paths[:]

    @property
    def ros_paths(self) -> builtins.list[str]:
        return self.get_ros_paths()

    def _locations(self) -> dict[str, str]:
        with _cache_lock:
            if self._location_cache is None:
                cache: dict[str, str] = {}
                for path in reversed(self._ros_paths):  # later paths first: the first path wins
                    list_by_path(self._manifest_name, path, cache)
                self._location_cache = cache
            return self._location_cache

    def list(self) -> builtins.list[str]:
        return list(self._locations())

    def get_path(self, name: str) -> str:
        """The folder of `name`; ResourceNotFound listing the ROS paths when there is none."""
        locations = self._locations()
        if name not in locations:
            raise ResourceNotFound(name, ros_paths=self._ros_paths)
        return locations[name]

    def get_manifest(self, name: str) -> Manifest:
        if name not in self._manifests:
            self._manifests[name] = parse_manifest_file(self.get_path(name), self._manifest_name, rospack=self)
        return self._manifests[name]

    def get_depends(self, name: str, implicit: bool = True) -> builtins.list[str]:
        """The names `name` depends on: directly, or (implicit) at any depth, unordered."""
        if not implicit:
            return [d.name for d in self.get_manifest(name).depends]
        if name in self._depends_cache:
            return self._depends_cache[name]
        direct = [d.name for d in self.get_manifest(name).depends]
        self._depends_cache[name] = []  # before recursing: a cycle ends here
        found: set[str] = set(direct)
        for dep in direct:
            found.update(self.get_depends(dep, implicit))
        self._depends_cache[name] = list(found)
        return self._depends_cache[name]

    def get_depends_on(self, name: str, implicit: bool = True) -> builtins.list[str]:
        """The resources that depend on `name` (bad manifests are passed over)."""
        depends_on = []
        for other in self.list():
            if other == name:
                continue
            try:
                deps = self.get_depends(other, implicit)
            except (InvalidManifest, ResourceNotFound):
                continue
            if name in deps:
                depends_on.append(other)
        return depends_on

    def get_custom_cache(self, key: str, default: Any = None) -> Any:
        return self._custom_cache.get(key, default)

    def set_custom_cache(self, key: str, value: Any) -> None:
        self._custom_cache[key] = value


class RosPack(ManifestManager):
    """The ROS packages (not metapackages) on the ROS paths."""

    def __init__(self, ros_paths: Sequence[str] | None = None) -> None:
        super().__init__(MANIFEST_FILE, ros_paths)

    def get_rosdeps(self, package: str, implicit: bool = True) -> builtins.list[str]:
        """The system dependencies of `package` (and, implicit, of its dependencies)."""
        names = [d.name for d in self.get_manifest(package).rosdeps]
        if implicit:
            for dep in self.get_depends(package, implicit=True):
                names.extend(d.name for d in self.get_manifest(dep).rosdeps)
        return list(dict.fromkeys(names))

    def stack_of(self, package: str) -> str | None:
        """The stack folder holding `package` (a stack.xml above it on its ROS path), or None."""
        folder = self.get_path(package)
        while True:
            if os.path.isfile(os.path.join(folder, STACK_FILE)):
                return os.path.basename(folder)
            parent = os.path.dirname(folder)
            if parent == folder or any(os.path.abspath(p) == folder for p in self._ros_paths):
                return None
            folder = parent


class RosStack(ManifestManager):
    """The metapackages (and rosbuild stacks) on the ROS paths."""

    def __init__(self, ros_paths: Sequence[str] | None = None) -> None:
        super().__init__(STACK_FILE, ros_paths)

    def packages_of(self, stack: str) -> builtins.list[str]:
        """The packages inside the stack's folder."""
        return list_by_path(MANIFEST_FILE, self.get_path(stack), None)

    def get_stack_version(self, stack: str) -> str | None:
        path = os.path.join(self.get_path(stack), PACKAGE_FILE)
        try:
            root = ElementTree.parse(path).getroot()
        except (ElementTree.ParseError, OSError):
            return None
        version = root.findtext("version")
        return version.strip() if version else None


def expand_to_packages(names: Sequence[str], rospack: RosPack, rosstack: RosStack) -> tuple[list[str], list[str]]:
    """(packages, names that are neither package nor stack): stacks expanded to their packages."""
    if not isinstance(names, (tuple, list)):
        raise ValueError("names must be a list of strings")
    known = rospack.list()
    packages: list[str] = []
    not_found: list[str] = []
    for name in names:
        if name in known:
            packages.append(name)
            continue
        try:
            packages.extend(rosstack.packages_of(name))
        except ResourceNotFound:
            not_found.append(name)
    return packages, not_found


def get_package_name(path: str) -> str | None:
    """The name of the package holding `path` (its nearest folder with a package.xml), or None."""
    folder = os.path.abspath(path)
    while True:
        manifest = os.path.join(folder, PACKAGE_FILE)
        if os.path.isfile(manifest):
            found = _package_xml_name(manifest)
            return found[0] if found else os.path.basename(folder)
        if os.path.isfile(os.path.join(folder, MANIFEST_FILE)):
            return os.path.basename(folder)
        parent = os.path.dirname(folder)
        if parent == folder:
            return None
        folder = parent
