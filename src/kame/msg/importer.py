"""Import hook: ROS packages on ROS_PACKAGE_PATH become importable with no build step.

`from beginner_tutorials.msg import Num` works for a package folder holding package.xml and
msg/Num.msg: the module beginner_tutorials.msg is made on import, and each class is
generated from its definition on first use (by the codegen that writes kame's own packages).
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
import threading
from collections.abc import Sequence
from types import ModuleType
from typing import Any

from kame.msg.catalog import SHARE_DIR, MsgCatalog, Package, find_packages, package_path_roots
from kame.msg.errors import MsgNotFoundError
from kame.msg.loader import compile_classes, dependency_order, make_service_class
from kame.msg.spec import MsgSpec

_KINDS = ("msg", "srv")
_lock = threading.RLock()
_crawled: dict[str, dict[str, Package]] = {}


def user_packages() -> dict[str, Package]:
    """The ROS packages on ROS_PACKAGE_PATH that have interface files, by name."""
    value = os.environ.get("ROS_PACKAGE_PATH", "")
    if not value:
        return {}
    with _lock:
        found = _crawled.get(value)
        if found is None:
            roots = [r for r in package_path_roots(value) if r != SHARE_DIR]
            found = {
                name: pkg for name, pkg in find_packages(roots).items()
                if any(pkg.interface_files(kind) for kind in (*_KINDS, "action"))
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


class InterfaceModule(ModuleType):
    """`pkg.msg` or `pkg.srv` of a user package: classes are generated on first access."""

    def __init__(self, name: str, package: Package, kind: str) -> None:
        super().__init__(name)
        self.__dict__["_kame_package"] = package
        self.__dict__["_kame_kind"] = kind

    def load_definitions(self) -> None:
        """(Re)read the package's definitions; classes made before are dropped."""
        for generated in self.__dict__.get("__all__", ()):
            self.__dict__.pop(generated, None)
        package: Package = self.__dict__["_kame_package"]
        catalog = MsgCatalog(find_packages(package_path_roots()))
        self.__dict__["_kame_catalog"] = catalog
        if self.__dict__["_kame_kind"] == "msg":
            names = [t.split("/")[1] for t in catalog.message_types(package.name)]
        else:
            names = []
            for t in catalog.service_types(package.name):
                short = t.split("/")[1]
                names += [short, short + "Request", short + "Response"]
        self.__dict__["__all__"] = sorted(names)

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__") or name not in self.__dict__["__all__"]:
            raise AttributeError(f"module {self.__name__!r} has no attribute {name!r}")
        with _lock:
            if name not in self.__dict__:
                self._generate(name)
        return self.__dict__[name]

    def __dir__(self) -> list[str]:
        return sorted(set(self.__dict__) | set(self.__dict__["__all__"]))

    def _generate(self, name: str) -> None:
        package: Package = self.__dict__["_kame_package"]
        catalog: MsgCatalog = self.__dict__["_kame_catalog"]
        if self.__dict__["_kame_kind"] == "msg":
            self._compile([catalog.msg_spec(f"{package.name}/{name}")])
            return
        service = name.removesuffix("Request").removesuffix("Response")
        srv = catalog.srv_spec(f"{package.name}/{service}")
        self._compile([srv.request, srv.response])
        self.__dict__[service] = make_service_class(
            srv, catalog.srv_md5sum(srv.full_name), self.__dict__[srv.request.short_name],
            self.__dict__[srv.response.short_name], self.__name__,
        )

    def _compile(self, specs: list[MsgSpec]) -> None:
        catalog: MsgCatalog = self.__dict__["_kame_catalog"]
        for spec in specs:
            catalog.check_dependencies(spec)
        own = {spec.full_name for spec in specs}
        ordered = dependency_order(specs, catalog.msg_spec, skip=lambda dep: dep not in own)
        external = {}
        for spec in ordered:
            for dep in spec.message_dependencies():
                if dep not in own:
                    external[dep] = _external_class(dep)
        classes = compile_classes(
            ordered, catalog.msg_spec, lambda s: catalog.md5sum(s.full_name),
            lambda s: catalog.full_text(s.full_name), external, self.__name__,
        )
        for type_name, cls in classes.items():
            self.__dict__[type_name.split("/")[1]] = cls


class _Loader(importlib.abc.Loader):
    def __init__(self, package: Package, kind: str | None) -> None:
        self.package = package
        self.kind = kind

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType:
        if self.kind is None:
            module = ModuleType(spec.name)
            module.__path__ = []
            return module
        return InterfaceModule(spec.name, self.package, self.kind)

    def exec_module(self, module: ModuleType) -> None:
        if isinstance(module, InterfaceModule):
            module.load_definitions()


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


def install() -> None:
    """Install the finders (kame.importhook does it at start-up; this is for other environments)."""
    import kame.importhook

    kame.importhook.install()
