"""Every public name of ROS 1's Python modules (roslaunch, rospy, genpy, genmsg, rosbag, roslib,
rosgraph, the tools) that kame lacks is in README's "ROS Python modules: names not provided",
with a reason; and nothing kame has is still there. scripts/module-surface.py walks Debian's
modules (under /usr/bin/python3) and looks each name up in kame's; run it by hand to see the list."""

from __future__ import annotations

import importlib.util
import re
import sys
from pathlib import Path
from types import ModuleType

import pytest

ROOT = Path(__file__).resolve().parents[1]
SECTION = "ROS Python modules: names not provided"
ENTRY = re.compile(r"^- ((?:`[^`]+`(?:, )?)+): (\S.*)$")


def surface_script() -> ModuleType:
    spec = importlib.util.spec_from_file_location("module_surface", ROOT / "scripts" / "module-surface.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def documented(readme: str) -> dict[str, str]:
    """README's list: each name (`module.name`, or `module` for a whole module) and its reason."""
    lines = readme.splitlines()
    start = next(i for i, line in enumerate(lines) if line.lstrip("#").strip() == SECTION and line.startswith("#"))
    names: dict[str, str] = {}
    for line in lines[start + 1:]:
        if line.startswith("#"):
            break
        found = ENTRY.match(line)
        if found:
            for name in re.findall(r"`([^`]+)`", found.group(1)):
                assert name not in names, f"{name} is listed twice"
                names[name] = found.group(2)
    return names


def test_the_readme_list_parses() -> None:
    names = documented((ROOT / "README.md").read_text())
    assert names and all(reason.strip() for reason in names.values())


def test_missing_names_are_the_documented_ones() -> None:
    surface = surface_script()
    packages = [p for p in surface.PACKAGES if surface.debian_has(p)]
    if not packages:
        pytest.skip("Debian's ROS Python modules are not installed")
    lacking = set(surface.missing(surface.debian_listing(packages)))
    listed = {name for name in documented((ROOT / "README.md").read_text()) if name.split(".")[0] in packages}
    assert not sorted(lacking - listed), "kame lacks these; provide them or give README a reason"
    assert not sorted(listed - lacking), "kame has these now; take them off README's list"
