"""Run at interpreter start-up (kame.pth): lets ROS packages on ROS_PACKAGE_PATH be imported.

Kept tiny on purpose: it runs in every Python process of the environment. Two finders are
added: one first on sys.meta_path that looks only at `X.msg`/`X.srv` names and dynamic_reconfigure's
`X.cfg`/`X.cfg.YConfig` (so a folder that merely looks like a namespace package cannot hide a
package's messages), one last
that looks at top-level names nobody else found. The message machinery is imported only
when such a name comes up while ROS_PACKAGE_PATH is set. Imports that fail while that
machinery is itself being imported (optional modules probed by the standard library) are
declined.
"""

from __future__ import annotations

import _thread
import os
import sys

TYPE_CHECKING = False  # not typing's: importing typing here would cost every interpreter start
if TYPE_CHECKING:
    from collections.abc import Sequence
    from importlib.machinery import ModuleSpec
    from types import ModuleType

_busy = _thread._local()


class _RosPackageFinder:
    """A meta path finder (no importlib.abc base: importing that costs every start-up)."""

    def __init__(self, submodules: bool) -> None:
        self.submodules = submodules

    def find_spec(
        self, fullname: str, path: Sequence[str] | None, target: ModuleType | None = None
    ) -> ModuleSpec | None:
        tail = fullname.partition(".")[2]
        cfg = tail == "cfg" or tail.startswith("cfg.")
        wanted = (tail in ("msg", "srv") or cfg) if self.submodules else not tail
        if not wanted:
            return None
        if not os.environ.get("ROS_PACKAGE_PATH") or getattr(_busy, "active", False):
            return None
        _busy.active = True
        try:
            if cfg:
                from kame.reconfigure import importer as cfg_importer

                return cfg_importer.CfgFinder().find_spec(fullname, path, target)
            from kame.msg import importer

            return importer.RosPackageFinder().find_spec(fullname, path, target)
        finally:
            _busy.active = False


class _XacroFinder:
    """xacro's `$(find pkg)` answered by kame's package finder in any process, so whichever `xacro`
    command runs: the xacro distribution's console script and kame's have one name, and the one
    installed last (an installer's order, a later `pip install -U xacro`) is the one on PATH."""

    def find_spec(
        self, fullname: str, path: Sequence[str] | None, target: ModuleType | None = None
    ) -> ModuleSpec | None:
        if fullname != "xacro":
            return None
        from importlib.machinery import PathFinder

        spec = PathFinder.find_spec(fullname, path, target)
        if spec is not None and spec.loader is not None:
            spec.loader = _ThenKamesFind(spec.loader)  # type: ignore[assignment]
        return spec


class _ThenKamesFind:
    def __init__(self, loader: object) -> None:
        self.loader = loader

    def create_module(self, spec: ModuleSpec) -> ModuleType | None:
        return self.loader.create_module(spec)  # type: ignore[attr-defined,no-any-return]

    def exec_module(self, module: ModuleType) -> None:
        self.loader.exec_module(module)  # type: ignore[attr-defined]
        from kame.cli.xacro import use_kame_packages

        use_kame_packages()


def install() -> None:
    if not any(isinstance(f, _RosPackageFinder) for f in sys.meta_path):
        sys.meta_path.insert(0, _RosPackageFinder(submodules=True))
        sys.meta_path.insert(1, _XacroFinder())
        sys.meta_path.append(_RosPackageFinder(submodules=False))


install()
