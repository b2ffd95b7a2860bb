"""kame.manifest and kame.depgraph: rospack's dependency rules on in-memory and small on-disk manifests."""

from __future__ import annotations

from pathlib import Path

import pytest

from kame.depgraph import DependencyError, DependencyGraph
from kame.manifest import Manifest, ManifestError, read_manifest

DEPS = {"a": ("c", "b", "libfoo"), "b": ("c", "d"), "c": ("d",), "d": ()}
CYCLE = {"x": ("y",), "y": ("z",), "z": ("y",)}


def graph(deps: dict[str, tuple[str, ...]] = DEPS) -> DependencyGraph:
    return DependencyGraph({n: Path(n) for n in deps},
                           read=lambda name, path: Manifest(name, path, "1.0.0", deps[name]))


def test_direct_closure_and_tree() -> None:
    g = graph()
    assert g.direct("a") == ["c", "b"]  # unknown names left out
    assert g.closure("a") == ["d", "c", "b"]
    assert g.indented("a") == ["c", "  d", "b", "  c", "    d", "  d"]
    assert g.dependents("d", direct=True) == ["b", "c"]
    assert g.dependents("d", direct=False) == ["a", "b", "c"]


def test_errors() -> None:
    with pytest.raises(DependencyError, match=r"^no such package q$"):
        graph().closure("q")
    with pytest.raises(DependencyError, match=r"likely circular dependency: y, z\)$"):
        graph(CYCLE).closure("x")
    with pytest.raises(DependencyError):
        graph({**DEPS, **CYCLE}).dependents("d", direct=False)  # as rospack: a cycle anywhere is an error


def test_manifest_formats(tmp_path: Path) -> None:
    (tmp_path / "package.xml").write_text(
        '<package format="2"><name>p</name><version>0.2.0</version><description>d</description>'
        '<maintainer email="a@b.c">m</maintainer><license>BSD</license>'
        "<depend>one</depend><exec_depend>two</exec_depend><build_depend>three</build_depend></package>")
    assert read_manifest("p", tmp_path) == Manifest("p", tmp_path, "0.2.0", ("two", "one"))
    (tmp_path / "package.xml").write_text("<package><name>p</name><run_depend>r</run_depend></package>")
    assert read_manifest("p", tmp_path).run_depends == ("r",)  # lenient: catkin_pkg refuses it
    (tmp_path / "package.xml").write_text("<package><name>p")
    with pytest.raises(ManifestError, match="error parsing manifest of package p at"):
        read_manifest("p", tmp_path)
