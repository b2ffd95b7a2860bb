"""roslib.manifestlib: rosbuild's manifest.xml and stack.xml, parsed and written back (for
roslib.manifest and roslib.stack_manifest). Dry packages and stacks are gone from Noetic, whose
catkin packages rospkg reads from package.xml; old tools still read these files with roslib."""

from __future__ import annotations

import os
import xml.dom.minidom as dom
from collections.abc import Callable
from typing import Any

from roslib.exceptions import ROSLibException

__all__ = ["ALLOWXHTML", "OPTIONAL", "REQUIRED", "VALID", "Depend", "Export", "ManifestException", "Platform",
           "ROSDep", "StackDepend", "VersionControl", "check", "check_depends", "check_exports", "check_optional",
           "check_platform", "check_required", "check_rosdeps", "check_stack_depends", "check_versioncontrol",
           "get_nodes_by_name", "parse", "parse_file"]

REQUIRED = ["author", "license"]
ALLOWXHTML = ["description"]
OPTIONAL = ["logo", "url", "brief", "description", "status", "notes", "depend", "rosdep", "export", "review",
            "versioncontrol", "platform", "version", "rosbuild2", "catkin"]
VALID = REQUIRED + OPTIONAL

Checker = Callable[[Any, str], Any]


class ManifestException(ROSLibException):
    """A manifest that is not valid."""


def get_nodes_by_name(n: Any, name: str) -> list[Any]:
    """The child elements of DOM node `n` named `name`."""
    return [t for t in n.childNodes if t.nodeType == t.ELEMENT_NODE and t.tagName == name]


def _get_text(nodes: Any) -> str:
    return "".join(n.data for n in nodes if n.nodeType == n.TEXT_NODE)


def _values(nodes: list[Any], allow_xhtml: bool) -> str:
    if allow_xhtml:
        return ", ".join("".join(x.toxml() for x in child.childNodes) for child in nodes)
    return ", ".join(_get_text(child.childNodes).strip() for child in nodes)


def check_optional(name: str, allowXHTML: bool = False, merge_multiple: bool = False) -> Checker:
    """The text of the optional element `name` (its XHTML with allowXHTML); several are an error
    unless merged (joined with ', ')."""
    def check(n: Any, filename: str) -> str | None:
        nodes = get_nodes_by_name(n, name)
        if len(nodes) > 1 and not merge_multiple:
            raise ManifestException(f"Invalid manifest file: must have a single '{name}' element")
        return _values(nodes, allowXHTML) if nodes else None

    return check


def check_required(name: str, allowXHTML: bool = False, merge_multiple: bool = False) -> Checker:
    """As check_optional, '' when absent."""
    def check(n: Any, filename: str) -> str:
        nodes = get_nodes_by_name(n, name)
        if not nodes:
            return ""
        if len(nodes) != 1 and not merge_multiple:
            raise ManifestException(f"Invalid manifest file: must have only one '{name}' element")
        return _values(nodes, allowXHTML)

    return check


def check_platform(name: str) -> Checker:
    def check(n: Any, filename: str) -> list[Platform]:
        try:
            return [Platform(p.attributes["os"].value, p.attributes["version"].value, p.getAttribute("notes"))
                    for p in get_nodes_by_name(n, name)]
        except KeyError as exc:
            raise ManifestException(f"<platform> tag is missing required '{exc}' attribute") from None

    return check


def check_depends(name: str) -> Checker:
    def check(n: Any, filename: str) -> list[Depend]:
        # rosbuild2's <depend thirdparty="..."/> names no package
        depends = [e.attributes for e in get_nodes_by_name(n, name) if "thirdparty" not in e.attributes.keys()]
        try:
            return [Depend(d["package"].value) for d in depends]
        except KeyError:
            raise ManifestException("Invalid manifest file: depends is missing 'package' attribute") from None

    return check


def check_stack_depends(name: str) -> Checker:
    def check(n: Any, filename: str) -> list[StackDepend]:
        return [StackDepend(e.attributes["stack"].value) for e in get_nodes_by_name(n, name)]

    return check


def check_rosdeps(name: str) -> Checker:
    def check(n: Any, filename: str) -> list[ROSDep]:
        return [ROSDep(e.attributes["name"].value) for e in get_nodes_by_name(n, name)]

    return check


def _attrs(node: Any) -> dict[str, str]:
    return {k: node.attributes.get(k).value for k in node.attributes.keys()}


def check_exports(name: str) -> Checker:
    def check(n: Any, filename: str) -> list[Export]:
        found = []
        for e in get_nodes_by_name(n, name):
            found += [Export(t.tagName, _attrs(t), _get_text(t.childNodes)) for t in e.childNodes
                      if t.nodeType == t.ELEMENT_NODE]
        return found

    return check


def check_versioncontrol(name: str) -> Checker:
    def check(n: Any, filename: str) -> VersionControl | None:
        e = get_nodes_by_name(n, name)
        if not e:
            return None
        return VersionControl(e[0].attributes["type"].value, e[0].attributes["url"].value)

    return check


def check(name: str, merge_multiple: bool = False) -> Checker:
    """The checker for element `name`."""
    special = {"depend": check_depends, "export": check_exports, "versioncontrol": check_versioncontrol,
               "rosdep": check_rosdeps, "platform": check_platform}
    if name in special:
        return special[name](name)
    if name in REQUIRED:
        return check_required(name, name in ALLOWXHTML, merge_multiple)
    if name in OPTIONAL:
        return check_optional(name, name in ALLOWXHTML, merge_multiple)
    raise ManifestException(f"no checker for the '{name}' element")


class Export:
    """An element inside <export>."""

    def __init__(self, tag: str, attrs: dict[str, str], str: str) -> None:
        self.tag = tag
        self.attrs = attrs
        self.str = str

    def get(self, attr: str) -> str | None:
        return self.attrs.get(attr, None)

    def xml(self) -> str:
        attrs = " ".join(f' {k}="{v}"' for k, v in self.attrs.items())
        if self.str:
            return f"<{self.tag}{attrs}>{self.str}</{self.tag}>"
        return f"<{self.tag}{attrs} />"


class Platform:
    """A <platform os version notes/> element."""

    __slots__ = ["notes", "os", "version"]

    def __init__(self, os: str, version: str, notes: str | None = None) -> None:
        if not os:
            raise ValueError("bad 'os' attribute")
        if not version:
            raise ValueError("bad 'version' attribute")
        self.os = os
        self.version = version
        self.notes = notes

    def __str__(self) -> str:
        return f"{self.os} {self.version}"

    __repr__ = __str__

    def __eq__(self, obj: object) -> bool:
        return isinstance(obj, Platform) and (self.os, self.version, self.notes) == (obj.os, obj.version, obj.notes)

    __hash__ = None  # type: ignore[assignment]

    def xml(self) -> str:
        if self.notes is not None:
            return f'<platform os="{self.os}" version="{self.version}" notes="{self.notes}"/>'
        return f'<platform os="{self.os}" version="{self.version}"/>'


class Depend:
    """A package's <depend package/>."""

    __slots__ = ["package"]

    def __init__(self, package: str) -> None:
        if not package:
            raise ValueError("bad 'package' attribute")
        self.package = package

    def __str__(self) -> str:
        return self.package

    __repr__ = __str__

    def __eq__(self, obj: object) -> bool:
        return isinstance(obj, Depend) and self.package == obj.package

    __hash__ = None  # type: ignore[assignment]

    def xml(self) -> str:
        return f'<depend package="{self.package}" />'


class StackDepend:
    """A stack's <depend stack/>."""

    __slots__ = ["annotation", "stack"]

    def __init__(self, stack: str) -> None:
        if not stack:
            raise ValueError("bad 'stack' attribute")
        self.stack = stack
        self.annotation: str | None = None

    def __str__(self) -> str:
        return self.stack

    __repr__ = __str__

    def __eq__(self, obj: object) -> bool:
        return isinstance(obj, StackDepend) and self.stack == obj.stack

    __hash__ = None  # type: ignore[assignment]

    def xml(self) -> str:
        if self.annotation:
            return f'<depend stack="{self.stack}" /> <!-- {self.annotation} -->'
        return f'<depend stack="{self.stack}" />'


class ROSDep:
    """A <rosdep name/>."""

    __slots__ = ["name"]

    def __init__(self, name: str) -> None:
        if not name:
            raise ValueError("bad 'name' attribute")
        self.name = name

    def xml(self) -> str:
        return f'<rosdep name="{self.name}" />'


class VersionControl:
    """A <versioncontrol type url/>."""

    __slots__ = ["type", "url"]

    def __init__(self, type_: str, url: str | None) -> None:
        if not type_ or not isinstance(type_, str):
            raise ValueError("bad 'type' attribute")
        if url is not None and not isinstance(url, str):
            raise ValueError("bad 'url' attribute")
        self.type = type_
        self.url = url

    def xml(self) -> str:
        if self.url:
            return f'<versioncontrol type="{self.type}" url="{self.url}" />'
        return f'<versioncontrol type="{self.type}" />'


class _Manifest:
    """A manifest.xml (`package`) or stack.xml (`stack`), as its fields."""

    __slots__ = ["_type", "author", "brief", "depends", "description", "exports", "license", "license_url", "logo",
                 "notes", "platforms", "rosdeps", "status", "unknown_tags", "url", "version", "versioncontrol"]

    def __init__(self, _type: str = "package") -> None:
        self.description = self.brief = self.author = self.license = self.license_url = ""
        self.url = self.logo = self.status = self.version = self.notes = ""
        self.depends: list[Any] = []
        self.rosdeps: list[ROSDep] = []
        self.exports: list[Export] = []
        self.platforms: list[Platform] = []
        self.versioncontrol: VersionControl | None = None
        self._type = _type
        self.unknown_tags: list[Any] = []

    def __str__(self) -> str:
        return self.xml()

    def get_export(self, tag: str, attr: str) -> list[str]:
        """The `attr` values of the exports named `tag`."""
        return [value for e in self.exports if e.tag == tag and (value := e.get(attr)) is not None]

    def xml(self) -> str:
        """The manifest written back as XML."""
        if not self.brief:
            desc = f"  <description>{self.description}</description>"
        else:
            desc = f'  <description brief="{self.brief}">{self.description}</description>'
        author = f"  <author>{self.author}</author>"
        if self.license_url:
            license_ = f'  <license url="{self.license_url}">{self.license}</license>'
        else:
            license_ = f"  <license>{self.license}</license>"
        review = f'  <review status="{self.status}" notes="{self.notes}" />' if self.status or self.notes else ""
        url = f"  <url>{self.url}</url>" if self.url else ""
        version = f"  <version>{self.version}</version>" if self.version else ""
        logo = f"  <logo>{self.logo}</logo>" if self.logo else ""
        depends = "\n".join(f"  {d.xml()}" for d in self.depends)
        rosdeps = "\n".join(f"  {rd.xml()}" for rd in self.rosdeps)
        platforms = "\n".join(f"  {p.xml()}" for p in self.platforms)
        exports = ("  <export>\n" + "\n".join(f"  {e.xml()}" for e in self.exports) + "  </export>"
                   if self.exports else "")
        versioncontrol = f"  {self.versioncontrol.xml()}" if self.versioncontrol else ""
        fields = [f for f in (desc, author, license_, review, url, logo, depends, rosdeps, platforms, exports,
                              versioncontrol, version) if f]
        return f"<{self._type}>\n" + "\n".join(fields) + f"\n</{self._type}>"


def parse_file(m: _Manifest, file: str) -> _Manifest:
    """Fill `m` from the manifest file `file`."""
    if not file:
        raise ValueError("Missing manifest file argument")
    if not os.path.isfile(file):
        raise ValueError(f"Invalid/non-existent manifest file: {file}")
    with open(file) as f:
        text = f.read()
    try:
        return parse(m, text, file)
    except ManifestException as exc:
        raise ManifestException(f"Invalid manifest file [{os.path.abspath(file)}]: {exc}") from None


def _attribute(p: Any, tag: str, name: str, default: str) -> str:
    nodes = get_nodes_by_name(p, tag)
    return str(nodes[0].getAttribute(name) or "") if nodes else default


def parse(m: _Manifest, string: str, filename: str = "string") -> _Manifest:
    """Fill `m` from manifest text `string`."""
    try:
        d = dom.parseString(string)
    except Exception as exc:  # whatever the XML parser refuses
        raise ManifestException(f"invalid XML: {exc}") from None
    roots = get_nodes_by_name(d, m._type)
    if len(roots) != 1:
        raise ManifestException(f"manifest must have a single '{m._type}' element")
    p = roots[0]
    m.description = check("description")(p, filename)
    m.brief = _attribute(p, "description", "brief", "")
    if m._type == "package":
        m.depends = check_depends("depend")(p, filename)
    elif m._type == "stack":
        m.depends = check_stack_depends("depend")(p, filename)
    m.rosdeps = check("rosdep")(p, filename)
    m.platforms = check("platform")(p, filename)
    m.exports = check("export")(p, filename)
    m.versioncontrol = check("versioncontrol")(p, filename)
    m.license = check("license")(p, filename)
    m.license_url = _attribute(p, "license", "url", "")
    m.status = _attribute(p, "review", "status", "unreviewed")
    m.notes = _attribute(p, "review", "notes", "")
    m.author = check("author", True)(p, filename)
    m.url = check("url")(p, filename)
    m.version = check("version")(p, filename)
    m.logo = check("logo")(p, filename)
    if m._type == "stack":
        if m.exports:
            raise ManifestException("stack manifests are not allowed to have exports")
        if m.rosdeps:
            raise ManifestException("stack manifests are not allowed to have rosdeps")
    m.unknown_tags = [e for e in p.childNodes if e.nodeType == e.ELEMENT_NODE and e.tagName not in VALID]
    return m
