"""A ROS package's package.xml as the package tools need it: name, version, run-time dependencies.

Read with catkin_pkg, the library ROS itself uses. The run-time dependencies are what rospack
follows, in its order: `<run_depend>` (format 1), or `<exec_depend>` then `<depend>` tags
(formats 2 and 3), each in document order. Like rospack, `condition` attributes are not
evaluated. A manifest that is well-formed XML but fails catkin_pkg's checks (no license, no
maintainer, ...) is still read, leniently, since rospack reads those too; one that is not XML
is a ManifestError.
"""

from __future__ import annotations

import xml.etree.ElementTree as ElementTree
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

MANIFEST = "package.xml"


class ManifestError(Exception):
    """A package.xml that cannot be read; the text is rospack's."""


@dataclass(frozen=True)
class Manifest:
    name: str
    path: Path
    version: str | None
    run_depends: tuple[str, ...]


def read_manifest(name: str, package_dir: Path) -> Manifest:
    """The manifest of package `name` found in `package_dir`."""
    path = package_dir / MANIFEST
    failure = ManifestError(f"error parsing manifest of package {name} at {path}")
    try:
        data = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise failure from exc
    from catkin_pkg.package import InvalidPackage, parse_package_string  # only when needed: it takes 40 ms

    try:
        package = parse_package_string(data, filename=str(path), warnings=[])
    except InvalidPackage:
        return _read_leniently(name, package_dir, data, failure)
    depends = _unique(dep.name for dep in package.exec_depends)
    return Manifest(name, package_dir, package.version, depends)


def _read_leniently(name: str, package_dir: Path, data: str, failure: ManifestError) -> Manifest:
    try:
        root = ElementTree.fromstring(data)
    except ElementTree.ParseError as exc:
        raise failure from exc
    if root.tag != "package":
        raise failure
    tags = ("run_depend",) if root.get("format", "1").strip() == "1" else ("exec_depend", "depend")
    names = [(el.text or "").strip() for tag in tags for el in root.findall(tag)]
    version = root.findtext("version")
    return Manifest(name, package_dir, version.strip() if version else None, _unique(n for n in names if n))


def _unique(names: Iterable[str]) -> tuple[str, ...]:
    return tuple(dict.fromkeys(names))
