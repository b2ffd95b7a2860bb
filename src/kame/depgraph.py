"""The run-time dependency graph of the ROS packages on the search path, as rospack walks it.

- Direct dependencies are a package's run-time dependencies (kame.manifest) that name a known
  package; other names (system dependencies such as libboost) are left out silently.
- The full closure is a depth-first walk listing each package after its own dependencies
  (rospack's post-order), each once.
- A dependency cycle is an error naming its members from the first one met again.
- Reverse dependencies are listed sorted by name (rospack's order there is its hash table's).
Manifests are read once, when first needed.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path

from kame.manifest import Manifest, read_manifest


class DependencyError(Exception):
    """A dependency question that has no answer; the text is rospack's."""


class DependencyGraph:
    def __init__(self, packages: Mapping[str, Path],
                 read: Callable[[str, Path], Manifest] = read_manifest) -> None:
        self.packages = dict(packages)
        self._read = read
        self._manifests: dict[str, Manifest] = {}

    def manifest(self, name: str) -> Manifest:
        found = self._manifests.get(name)
        if found is None:
            path = self.packages.get(name)
            if path is None:
                raise DependencyError(f"no such package {name}")
            found = self._manifests[name] = self._read(name, path)
        return found

    def direct(self, name: str) -> list[str]:
        return [dep for dep in self.manifest(name).run_depends if dep in self.packages]

    def closure(self, name: str) -> list[str]:
        """Every package `name` depends on, dependencies before their dependents."""
        order: list[str] = []
        seen: set[str] = set()

        def visit(pkg: str, stack: list[str]) -> None:
            for dep in self.direct(pkg):
                if dep in stack:
                    cycle = stack[stack.index(dep):]
                    raise DependencyError(
                        f"maximum dependency depth exceeded (likely circular dependency: {', '.join(cycle)})")
                if dep not in seen:
                    seen.add(dep)
                    visit(dep, [*stack, dep])
                    order.append(dep)

        visit(name, [name])
        return order

    def indented(self, name: str) -> list[str]:
        """The whole dependency tree, two spaces per level, repeats included (depends-indent)."""
        self.closure(name)  # refuses cycles first
        lines: list[str] = []

        def visit(pkg: str, depth: int) -> None:
            for dep in self.direct(pkg):
                lines.append("  " * depth + dep)
                visit(dep, depth + 1)

        visit(name, 0)
        return lines

    def dependents(self, name: str, *, direct: bool) -> list[str]:
        """The packages that depend on `name`: directly, or at any depth."""
        if name not in self.packages:
            raise DependencyError(f"no such package {name}")
        found = []
        for other in sorted(self.packages):
            if other == name:
                continue
            deps = self.direct(other) if direct else self.closure(other)
            if name in deps:
                found.append(other)
        return found
