"""The layering of docs/ARCHITECTURE.md, enforced: imports point down, pure layers stay pure.

L0 foundations (msg, names, time values) and L1 pure logic (protocol codecs, the master's
registry and parameter tree, ...) never import I/O, concurrency or clock modules. net/ (L2)
moves bytes and knows nothing of messages or the master. Every module of kame must have a
layer here: a new module fails this test until it is placed.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"

# Most specific prefix wins.
LAYERS: dict[str, int] = {
    "kame": 0,
    "kame.msg": 0,
    "kame.names": 0,
    "kame.rostime": 0,
    "kame.protocol": 1,
    "kame.bag": 1,  # the bag record format, compression, info text
    "kame.bag.reader": 2,  # bag file I/O
    "kame.bag.writer": 2,
    "kame.action": 1,
    "kame.master": 1,
    "kame.net": 2,
    "kame.node": 3,
    "kame.master.server": 3,
    "kame.cli": 4,
    "kame.importhook": 4,
    "kame.launch": 1,
    "kame.launch.supervisor": 2,
    "kame.launch.server": 2,  # the roslaunch XML-RPC server
    "kame.launch.runner": 4,
    "kame.catkin": 2,
    "kame.shell": 4,
    "kame.tf": 1,  # transformations and the tf2 buffer core: no clock, no threads
    "kame.tf_ros": 3,  # the Buffer that waits, /tf listener and broadcasters on a Node
    "kame.share": 4,  # programs shipped in ROS packages (scripts/*.py)
    "kame.turtle_tf": 4,  # the turtle_tf demo programs
    "kame.turtlesim": 1,  # the world: no ROS, no GUI, no clock
    "kame.turtlesim.gui": 4,  # Qt; knows only the world
    "kame.turtlesim.node": 4,
    "kame.turtlesim.teleop_key": 4,
    "kame.turtlesim.draw_square": 4,
    "kame.turtlesim.mimic": 4,
}
PURE_FORBIDDEN = {"socket", "select", "selectors", "asyncio", "threading", "subprocess", "signal", "time",
                  "multiprocessing", "concurrent"}  # datetime is allowed: YAML dates are values
NET_FORBIDDEN = ("kame.msg", "kame.master", "kame.node")


def layer_of(module: str) -> int:
    best = ""
    for prefix in LAYERS:
        if (module == prefix or module.startswith(prefix + ".")) and len(prefix) > len(best):
            best = prefix
    if not best:
        raise KeyError(module)
    return LAYERS[best]


def kame_modules() -> list[tuple[str, Path]]:
    found = []
    for path in sorted((SRC / "kame").rglob("*.py")):
        rel = path.relative_to(SRC).with_suffix("")
        parts = list(rel.parts)
        if parts[-1] == "__init__":
            parts.pop()
        found.append((".".join(parts), path))
    return found


def imports_of(path: Path, module: str) -> set[str]:
    tree = ast.parse(path.read_text(), str(path))
    names: set[str] = set()
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            source = node.module or ""
            if node.level:
                base = package.split(".")
                base = base[: len(base) - (node.level - 1)]
                source = ".".join([*base, source]) if source else ".".join(base)
            names.add(source)
            names.update(f"{source}.{alias.name}" for alias in node.names)
    return names


MODULES = kame_modules()


def test_every_module_has_a_layer() -> None:
    unplaced = []
    for module, _ in MODULES:
        try:
            layer_of(module)
        except KeyError:
            unplaced.append(module)
    assert unplaced == [], "add these modules to LAYERS in tests/test_layers.py"


@pytest.mark.parametrize(("module", "path"), MODULES, ids=[m for m, _ in MODULES])
def test_imports_point_down(module: str, path: Path) -> None:
    own = layer_of(module)
    upward = sorted(
        name for name in imports_of(path, module)
        if name.startswith("kame.") and _known(name) and layer_of(name) > own
    )
    assert upward == [], f"{module} (L{own}) imports from a higher layer"


@pytest.mark.parametrize(("module", "path"), MODULES, ids=[m for m, _ in MODULES])
def test_pure_layers_do_no_io(module: str, path: Path) -> None:
    if layer_of(module) > 1:
        return
    forbidden = sorted(name for name in imports_of(path, module) if name.split(".")[0] in PURE_FORBIDDEN)
    assert forbidden == [], f"{module} is in a pure layer but imports {forbidden}"


@pytest.mark.parametrize(("module", "path"), MODULES, ids=[m for m, _ in MODULES])
def test_net_knows_nothing_of_messages_or_the_master(module: str, path: Path) -> None:
    if not module.startswith("kame.net"):
        return
    assert [n for n in imports_of(path, module) if n.startswith(NET_FORBIDDEN)] == []


def _known(name: str) -> bool:
    try:
        layer_of(name)
    except KeyError:
        return False
    return True


def test_the_checker_catches_a_violation(tmp_path: Path) -> None:
    bad = tmp_path / "bad.py"
    bad.write_text("import socket\nfrom kame.cli import rosmsg\nfrom . import sibling\n")
    names = imports_of(bad, "kame.msg.bad")
    assert {"socket", "kame.cli", "kame.cli.rosmsg", "kame.msg.sibling"} <= names
    assert layer_of("kame.cli.rosmsg") > layer_of("kame.msg.bad")
