"""rospkg.manifest: a package's package.xml as rospkg's Manifest (read with catkin_pkg).

rospkg files a catkin package's dependencies only when rosdep is installed, and then lists the
build tool, build, run and test dependencies that are ROS packages; kame's always does, naming
those found by the RosPack asking. Only package.xml is read (rosbuild manifest.xml is not).
"""

from __future__ import annotations

import os
from typing import Any, Protocol

from .common import MANIFEST_FILE, PACKAGE_FILE, STACK_FILE

__all__ = ["MANIFEST_FILE", "PACKAGE_FILE", "STACK_FILE", "Depend", "Export", "InvalidManifest", "Manifest",
           "RosDep", "parse_manifest_file"]


class PackageLister(Protocol):
    """What parse_manifest_file asks of the RosPack (rospkg.rospack's ManifestManager) asking."""

    def list(self) -> list[str]: ...


class InvalidManifest(Exception):
    """A manifest that cannot be read."""


class Depend:
    """A dependency on a package (or stack) by name."""

    __slots__ = ("name", "type")

    def __init__(self, name: str, type_: str) -> None:
        if not name:
            raise ValueError(f"bad '{type_}' attribute")
        if not type_:
            raise ValueError("type_ must be specified")
        self.name = name
        self.type = type_

    def __str__(self) -> str:
        return self.name

    __repr__ = __str__

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Depend) and (self.name, self.type) == (other.name, other.type)

    def __hash__(self) -> int:
        return hash(self.name) ^ hash(self.type)


class RosDep:
    """A system dependency (rosdep key)."""

    __slots__ = ("name",)

    def __init__(self, name: str) -> None:
        if not name:
            raise ValueError("bad 'name' attribute")
        self.name = name


class Export:
    """An `<export>` tag: tag name, attributes and text (upstream calls it `str`)."""

    __slots__ = ("attrs", "str", "tag")

    def __init__(self, tag: str, attrs: dict[str, str], str: str | None) -> None:
        self.tag = tag
        self.attrs = attrs
        self.str = str

    def get(self, attr: str) -> str | None:
        return self.attrs.get(attr)


class Manifest:
    """What rospkg knows of a package: description, authors, licenses, version, depends, exports."""

    def __init__(self, type_: str = "package", filename: str | None = None, is_catkin: bool = False) -> None:
        self.description = self.brief = self.author = self.license = self.license_url = ""
        self.url = self.status = self.version = self.notes = ""
        self.licenses: list[str] = []
        self.depends: list[Depend] = []
        self.rosdeps: list[RosDep] = []
        self.exports: list[Export] = []
        self.platforms: list[Any] = []
        self.unknown_tags: list[Any] = []
        self.is_catkin = is_catkin
        self.type = type_
        self.filename = filename

    def get_export(self, tag: str, attr: str) -> list[str]:
        """The `attr` values of the `<tag>` exports."""
        return [value for e in self.exports if e.tag == tag and (value := e.get(attr)) is not None]


def parse_manifest_file(dirpath: str, manifest_name: str, rospack: PackageLister | None = None) -> Manifest:
    """The manifest of the package in `dirpath`; IOError without a package.xml; catkin_pkg's
    InvalidPackage for one it refuses, as upstream."""
    from catkin_pkg.package import parse_package

    filename = os.path.join(dirpath, manifest_name)
    package_file = os.path.join(dirpath, PACKAGE_FILE)
    if not os.path.isfile(package_file):
        raise OSError(f"Invalid/non-existent manifest file: {filename}")
    package = parse_package(package_file)
    manifest = Manifest(filename=filename, is_catkin=True)
    manifest.description = package.description
    manifest.author = ", ".join([f"Maintainer: {m}" for m in package.maintainers] + [str(a) for a in package.authors])
    manifest.licenses = [str(license) for license in package.licenses]
    manifest.license = ", ".join(manifest.licenses)
    if package.urls:
        manifest.url = str(package.urls[0])
    manifest.version = package.version
    manifest.exports = [Export(e.tagname, dict(e.attributes), e.content) for e in package.exports]
    known = set(rospack.list()) if rospack is not None else set()
    names = [d.name for d in package.buildtool_depends + package.build_depends + package.run_depends
             + package.test_depends]
    for name in dict.fromkeys(names):
        if name in known:
            manifest.depends.append(Depend(name, "package"))
        else:
            manifest.rosdeps.append(RosDep(name))
    return manifest
