"""Import hook: ROS packages on ROS_PACKAGE_PATH become importable with no build step.

`from beginner_tutorials.msg import Num` works for a package folder holding package.xml and
msg/Num.msg: the module beginner_tutorials.msg is made on import, its classes generated from
the definitions by the codegen that writes kame's own packages.
Types from other packages come from their own modules, so a user message holding a Header
uses std_msgs.msg.Header itself. Nothing is cached on disk: every process, and every
importlib.reload(), reads the definitions afresh, so edited .msg files are always seen.

Real Python modules always keep their place: kame's own generated packages, and a Python
package of the same name (catkin_python_setup code), whose missing .msg/.srv submodules
are supplied from here. A folder that only looks like a namespace package (running Python
from inside a workspace's src/) does not hide a ROS package's messages.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import os
from collections.abc import Sequence
from types import ModuleType
from typing import Any

from kame.msg.catalog import SHARE_DIR, MsgCatalog, Package, find_packages, package_path_roots
from kame.msg.errors import MsgNotFoundError
from kame.msg.loader import compile_classes, dependency_order, make_service_class
from kame.msg.md5 import all_dependencies
from kame.msg.spec import MsgSpec

_KINDS = ("msg", "srv")
_crawled: dict[str, dict[str, Package]] = {}


def user_packages() -> dict[str, Package]:
    """The ROS packages on ROS_PACKAGE_PATH that have interface files (or dynamic_reconfigure .cfg files), by name."""
    value = os.environ.get("ROS_PACKAGE_PATH", "")
    if not value:
        return {}
    found = _crawled.get(value)
    if found is None:
        roots = [r for r in package_path_roots(value) if r != SHARE_DIR]
        found = {
            name: pkg for name, pkg in find_packages(roots).items()
            if any(pkg.interface_files(kind) for kind in (*_KINDS, "action", "cfg"))
        }
        _crawled[value] = found
    return found


def _external_class(type_name: str) -> type[Any]:
    package, short = type_name.split("/")
    module = importlib.import_module(f"{package}.msg")
    try:
        cls: type[Any] = getattr(module, short)
    except AttributeError:
        raise MsgNotFoundError(f"message type {type_name} not found in module {package}.msg") from None
    return cls


def _message_classes(catalog: MsgCatalog, specs: list[MsgSpec], module_name: str) -> dict[str, type[Any]]:
    for spec in specs:
        catalog.check_dependencies(spec)
    own = {spec.full_name for spec in specs}
    ordered = dependency_order(specs, catalog.msg_spec, skip=lambda dep: dep not in own)
    # every type the classes build, nested ones included: the generated code makes a field's
    # field's message itself (a service's request holding pkg/A, whose field is other_pkg/B)
    external = {
        dep: _external_class(dep) for spec in ordered for dep in all_dependencies(spec, catalog.msg_spec)
        if dep not in own
    }
    return compile_classes(
        ordered, catalog.msg_spec, lambda s: catalog.md5sum(s.full_name),
        lambda s: catalog.full_text(s.full_name), external, module_name,
    )


def load_interfaces(module: ModuleType, package: Package, kind: str) -> None:
    """Fill `pkg.msg` or `pkg.srv` with classes generated from the package's definitions.

    Everything is generated while the module is imported, under the import system's lock,
    so threads importing the same package get the same classes.
    """
    catalog = MsgCatalog(find_packages(package_path_roots()))
    names: dict[str, Any] = {}
    if kind == "msg":
        specs = [catalog.msg_spec(t) for t in catalog.message_types(package.name)]
        for type_name, cls in _message_classes(catalog, specs, module.__name__).items():
            names[type_name.split("/")[1]] = cls
    else:
        for srv_type in catalog.service_types(package.name):
            srv = catalog.srv_spec(srv_type)
            classes = _message_classes(catalog, [srv.request, srv.response], module.__name__)
            request, response = classes[srv.request.full_name], classes[srv.response.full_name]
            names[srv.request.short_name] = request
            names[srv.response.short_name] = response
            names[srv.short_name] = make_service_class(
                srv, catalog.srv_md5sum(srv_type), request, response, module.__name__
            )
    for stale in getattr(module, "__all__", ()):
        module.__dict__.pop(stale, None)
    module.__dict__.update(names)
    module.__all__ = sorted(names)  # type: ignore[attr-defined]


class _Loader(importlib.abc.Loader):
    def __init__(self, package: Package, kind: str | None) -> None:
        self.package = package
        self.kind = kind

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType:
        module = ModuleType(spec.name)
        if self.kind is None:
            module.__path__ = []
        return module

    def exec_module(self, module: ModuleType) -> None:
        if self.kind is not None:
            load_interfaces(module, self.package, self.kind)


class RosPackageFinder(importlib.abc.MetaPathFinder):
    def find_spec(
        self, fullname: str, path: Sequence[str] | None, target: ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        head, _, tail = fullname.partition(".")
        if (tail and tail not in _KINDS) or not os.environ.get("ROS_PACKAGE_PATH"):
            return None
        package = user_packages().get(head)
        if package is None:
            return None
        if not tail:
            return importlib.machinery.ModuleSpec(fullname, _Loader(package, None), is_package=True)
        if not package.interface_files(tail) and not (tail == "msg" and package.interface_files("action")):
            return None
        existing = importlib.machinery.PathFinder.find_spec(fullname, path)
        if existing is not None and existing.loader is not None:
            return None  # real Python modules (generated ones, kame's own) keep their place
        return importlib.machinery.ModuleSpec(fullname, _Loader(package, tail))
