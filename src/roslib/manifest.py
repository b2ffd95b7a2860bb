"""roslib.manifest: a rosbuild package's manifest.xml (see roslib.manifestlib)."""

from __future__ import annotations

import os
from collections.abc import Mapping

from roslib import manifestlib
from roslib import packages as _packages
from roslib.manifestlib import Depend, Export, ManifestException, ROSDep, VersionControl

__all__ = ["MANIFEST_FILE", "Depend", "Export", "Manifest", "ManifestException", "ROSDep", "VersionControl",
           "load_manifest", "manifest_file", "parse", "parse_file"]

MANIFEST_FILE = "manifest.xml"


class Manifest(manifestlib._Manifest):
    """A package's manifest.xml."""

    __slots__: list[str] = []

    def __init__(self) -> None:
        super().__init__("package")


def _manifest_file_by_dir(package_dir: str, required: bool = True) -> str | None:
    path = os.path.join(package_dir, MANIFEST_FILE)
    if not required and not os.path.exists(path):
        return path
    if not os.path.isfile(path):
        if required:
            raise _packages.InvalidROSPkgException(
                f"\nPackage '{package_dir}' is improperly configured: no manifest file is present.\n")
        return None
    return path


def manifest_file(package: str, required: bool = True, env: Mapping[str, str] | None = None) -> str | None:
    """The path of `package`'s manifest.xml; InvalidROSPkgException (None when not `required`)
    when the package or its manifest.xml is missing."""
    env = os.environ if env is None else env
    package_dir = _packages.get_pkg_dir(package, required, ros_root=env.get("ROS_ROOT"))
    if package_dir is None:
        return None
    return _manifest_file_by_dir(package_dir, required=required)


def load_manifest(package: str) -> Manifest:
    """The manifest of `package`."""
    return parse_file(str(manifest_file(package)))


def parse_file(file: str) -> Manifest:
    m = manifestlib.parse_file(Manifest(), file)
    assert isinstance(m, Manifest)
    return m


def parse(string: str, filename: str = "string") -> Manifest:
    """The manifest in text `string`; a <version> is refused, as in rosbuild's packages."""
    m = manifestlib.parse(Manifest(), string, filename)
    assert isinstance(m, Manifest)
    if m.version:
        raise ManifestException("<version> tag is not valid in a package manifest.xml file")
    return m
