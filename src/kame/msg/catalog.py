"""Where message definitions live: ROS packages on ROS_PACKAGE_PATH and kame's own.

A package is a folder holding a package.xml; its interface files are msg/*.msg, srv/*.srv
and action/*.action. ROS_PACKAGE_PATH entries are searched first, in order (the first
package of a name wins, as with rospack), then the packages kame ships in kame/share.
Programs kame ships for a package that are not in its share folder (roscpp_tutorials' talker,
...) are in kame/lib/<package>, as an installed ROS keeps them in lib/<package>.
Folders holding CATKIN_IGNORE, and hidden folders, are not searched; nor are the subfolders of
one holding rospack_nosubdirs.
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ElementTree
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

from kame.msg.errors import MsgDefinitionError, MsgNotFoundError
from kame.msg.md5 import Md5Cache, full_text
from kame.msg.parser import action_message_texts, parse_msg, parse_srv, split_type_name
from kame.msg.spec import MsgSpec, SrvSpec

SHARE_DIR = Path(__file__).resolve().parent.parent / "share"
LIB_DIR = SHARE_DIR.parent / "lib"


def shipped_programs(package: str) -> list[Path]:
    """kame's folder of `package`'s programs (as lib/<package> of an installed ROS), if it has one."""
    folder = LIB_DIR / package
    return [folder] if folder.is_dir() else []
_ACTION_SUFFIXES = ("ActionGoal", "ActionResult", "ActionFeedback", "Action", "Goal", "Result", "Feedback")


@dataclass(frozen=True)
class Package:
    name: str
    path: Path

    def interface_files(self, kind: str) -> list[Path]:
        """The package's files of one kind ('msg', 'srv' or 'action'), sorted by name."""
        folder = self.path / kind
        if not folder.is_dir():
            return []
        return sorted(p for p in folder.iterdir() if p.suffix == "." + kind and p.is_file())


def read_package_name(package_xml: Path) -> str | None:
    try:
        root = ElementTree.parse(package_xml).getroot()
    except (ElementTree.ParseError, OSError):
        return None
    name = root.findtext("name")
    return name.strip() if name else None


@dataclass(frozen=True)
class CrawlStep:
    """One step of a crawl: a folder entered ("enter"), left ("leave", with whether any package
    was found below it), or a package found ("package")."""

    kind: str
    path: Path
    package: Package | None = None
    found_any: bool = False


def crawl(root: Path) -> Iterator[CrawlStep]:
    """Walk one search-path entry as rospack does, yielding each step (for timing or listing).

    Package folders are not entered further; CATKIN_IGNORE and rospack_nosubdirs stop the
    descent, hidden folders are skipped; folders are visited in name order.
    """
    if not root.is_dir() or (root / "CATKIN_IGNORE").exists():
        return
    manifest = root / "package.xml"
    if manifest.is_file():
        name = read_package_name(manifest) or root.name
        yield CrawlStep("package", root, Package(name, root))
        return
    yield CrawlStep("enter", root)
    found_any = False
    children: list[Path] = []
    if not (root / "rospack_nosubdirs").exists():
        try:
            children = sorted(root.iterdir())
        except OSError:
            children = []
    for child in children:
        if child.is_dir() and not child.name.startswith("."):
            for step in crawl(child):
                if step.path.parent == root and (step.kind == "package" or (step.kind == "leave" and step.found_any)):
                    found_any = True
                yield step
    yield CrawlStep("leave", root, found_any=found_any)


def _crawl(root: Path, found: dict[str, Package]) -> None:
    for step in crawl(root):
        if step.package is not None:
            found.setdefault(step.package.name, step.package)


def package_path_roots(ros_package_path: str | None = None) -> list[Path]:
    value = os.environ.get("ROS_PACKAGE_PATH", "") if ros_package_path is None else ros_package_path
    roots = [Path(p) for p in value.split(os.pathsep) if p]
    return [*roots, SHARE_DIR]


def find_packages(roots: Iterable[Path]) -> dict[str, Package]:
    found: dict[str, Package] = {}
    for root in roots:
        _crawl(root, found)
    return found


class MsgCatalog:
    """Loads and caches the specs of the types found in a set of packages."""

    def __init__(self, packages: Mapping[str, Package]) -> None:
        self.packages = dict(packages)
        self._msgs: dict[str, MsgSpec] = {}
        self._srvs: dict[str, SrvSpec] = {}
        self._md5 = Md5Cache(self.msg_spec)

    @classmethod
    def from_environment(cls, ros_package_path: str | None = None) -> MsgCatalog:
        return cls(find_packages(package_path_roots(ros_package_path)))

    def add_spec(self, spec: MsgSpec) -> None:
        """Make a spec known that no package file provides (e.g. from a message_definition)."""
        self._msgs.setdefault(spec.full_name, spec)

    def add_srv_spec(self, spec: SrvSpec) -> None:
        """Make a service spec (and its request and response) known that no package file provides."""
        self._srvs.setdefault(spec.full_name, spec)
        self.add_spec(spec.request)
        self.add_spec(spec.response)

    def _package(self, package: str, short: str) -> Package:
        found = self.packages.get(package)
        if found is None:
            paths = [str(p.path.parent) for p in self.packages.values()]
            raise MsgNotFoundError(
                f"Cannot locate message [{short}]: unknown package [{package}] on search path [{sorted(set(paths))}]"
            )
        return found

    def msg_spec(self, full_name: str) -> MsgSpec:
        spec = self._msgs.get(full_name)
        if spec is not None:
            return spec
        try:
            package_name, short = split_type_name(full_name)
        except ValueError as exc:
            raise MsgNotFoundError(str(exc)) from None
        package = self._package(package_name, short)
        path = package.path / "msg" / f"{short}.msg"
        if path.is_file():
            spec = parse_msg(_read(path), full_name, str(path))
        else:
            spec = self._action_message(package, short)
            if spec is None:
                raise MsgNotFoundError(
                    f"Cannot locate message [{short}] in package [{package_name}] "
                    f"with paths [[{str(package.path / 'msg')!r}]]"
                )
        self._msgs[full_name] = spec
        return spec

    def _action_message(self, package: Package, short: str) -> MsgSpec | None:
        for suffix in _ACTION_SUFFIXES:
            if short.endswith(suffix) and len(short) > len(suffix):
                action = short[: -len(suffix)]
                path = package.path / "action" / f"{action}.action"
                if path.is_file():
                    texts = action_message_texts(_read(path), action, str(path))
                    for name, body in texts.items():
                        self._msgs.setdefault(
                            f"{package.name}/{name}", parse_msg(body, f"{package.name}/{name}", str(path))
                        )
                    return self._msgs.get(f"{package.name}/{short}")
        return None

    def srv_spec(self, full_name: str) -> SrvSpec:
        spec = self._srvs.get(full_name)
        if spec is not None:
            return spec
        try:
            package_name, short = split_type_name(full_name)
        except ValueError as exc:
            raise MsgNotFoundError(str(exc)) from None
        package = self._package(package_name, short)
        path = package.path / "srv" / f"{short}.srv"
        if not path.is_file():
            raise MsgNotFoundError(
                f"Cannot locate message [{short}] in package [{package_name}] "
                f"with paths [[{str(package.path / 'srv')!r}]]"
            )
        spec = parse_srv(_read(path), full_name, str(path))
        self._srvs[full_name] = spec
        self._msgs.setdefault(spec.request.full_name, spec.request)
        self._msgs.setdefault(spec.response.full_name, spec.response)
        return spec

    def check_dependencies(self, spec: MsgSpec) -> None:
        """Load every type `spec` uses; a missing one is named with the file that needs it."""
        pending = [spec]
        seen = {spec.full_name}
        while pending:
            current = pending.pop()
            for dep in current.message_dependencies():
                if dep in seen:
                    continue
                seen.add(dep)
                try:
                    pending.append(self.msg_spec(dep))
                except MsgNotFoundError as exc:
                    where = current.source or current.full_name
                    raise MsgNotFoundError(
                        f"{where}: {current.full_name} uses the type {dep}, which cannot be found: {exc}"
                    ) from exc

    def md5sum(self, full_name: str) -> str:
        return self._md5.md5sum_of(full_name)

    def md5_text(self, full_name: str) -> str:
        return self._md5.md5_text(self.msg_spec(full_name))

    def srv_md5sum(self, full_name: str) -> str:
        return self._md5.srv_md5sum(self.srv_spec(full_name))

    def full_text(self, full_name: str) -> str:
        return full_text(self.msg_spec(full_name), self.msg_spec)

    def message_types(self, package: str) -> list[str]:
        """Every message type of a package, action-generated ones included, sorted."""
        pkg = self.packages[package]
        names = {p.stem for p in pkg.interface_files("msg")}
        for action in pkg.interface_files("action"):
            names.update(f"{action.stem}{suffix}" for suffix in _ACTION_SUFFIXES)
        return [f"{package}/{n}" for n in sorted(names)]

    def service_types(self, package: str) -> list[str]:
        pkg = self.packages[package]
        return [f"{package}/{p.stem}" for p in pkg.interface_files("srv")]

    def action_types(self, package: str) -> list[str]:
        pkg = self.packages[package]
        return [f"{package}/{p.stem}" for p in pkg.interface_files("action")]


def _read(path: Path) -> str:
    try:
        return path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise MsgDefinitionError(f"{path}: cannot read: {exc}") from exc
