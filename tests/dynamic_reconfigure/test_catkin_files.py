"""The files catkin's build writes from a .cfg (Config module, C++ header, three docs), byte for byte
as Debian's parameter_generator_catkin writes them: the .cfg run with catkin's arguments, and catkin_make."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from kame.msg.catalog import SHARE_DIR

from ..cli.test_catkin import make_workspace, run
from ..shell.shell_env import bash
from .test_cfg_import import SYSTEM_PYTHON, TUTORIAL_CFG, TUTORIAL_PACKAGE, debian_has_generator

DEBIAN_DYNAMIC_RECONFIGURE = Path("/usr/share/dynamic_reconfigure")
KAME_TEMPLATES = SHARE_DIR / "dynamic_reconfigure" / "templates"
needs_debian = pytest.mark.skipif(not debian_has_generator(), reason="Debian's python3-dynamic-reconfigure is missing")

# What the tutorial's cfg does not reach: a double with no default or limits (upstream's int 0 and
# C++ infinities), bool False, an edit_method that is no enum, a str enum, a hidden group that is
# off, a nested tab, a double constant.
EDGE_CFG = '''#!/usr/bin/env python
PACKAGE = "edge_pkg"
from dynamic_reconfigure.parameter_generator_catkin import *
gen = ParameterGenerator()
gen.add("rate", double_t, 1, "Rate with no limits")
gen.add("flag", bool_t, 0, "Off by default", False)
gen.add("count", int_t, 0, "Count", 3, edit_method="not an enum")
mode = gen.enum([gen.const("Fast", str_t, "fast", "Go fast"), gen.const("Slow", str_t, "slow", "Go slow")], "Modes")
gen.add("mode", str_t, 8, "Mode", "fast", edit_method=mode)
hidden = gen.add_group("Hidden Stuff", type="hide", state=False)
hidden.add("gain", double_t, 16, "Gain", -1.5, -10)
tab = hidden.add_group("tab", type="tab")
tab.add("ratio", double_t, 0, "Ratio", 0.25, 0, 1)
gen.const("Pi", double_t, 3.14159, "pi")
exit(gen.generate(PACKAGE, "edge_node", "Edge"))
'''


def tree(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


def debian_templates_dir() -> Path:
    """Debian's dynamic_reconfigure folder with its templates, else kame's (the generator is Debian's either way)."""
    if (DEBIAN_DYNAMIC_RECONFIGURE / "templates" / "ConfigType.h.template").is_file():
        return DEBIAN_DYNAMIC_RECONFIGURE
    return KAME_TEMPLATES.parent


def run_cfg(python: str, cfg: Path, out: Path) -> subprocess.CompletedProcess[str]:
    """The command catkin's CMake runs: `<cfg> <dynamic_reconfigure> <share> <include> <python>`."""
    (out / "cwd").mkdir(parents=True)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "ROS_PACKAGE_PATH")}
    args = [python, str(cfg), str(debian_templates_dir()), str(out / "share"), str(out / "include"), str(out / "py")]
    result = subprocess.run(args, cwd=out / "cwd", env=env, capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stdout + result.stderr
    return result


@pytest.mark.skipif(not (DEBIAN_DYNAMIC_RECONFIGURE / "templates").is_dir(),
                    reason="Debian's libdynamic-reconfigure-config-init-mutex-dev (the templates) is missing")
def test_shipped_templates_are_upstreams() -> None:
    names = sorted(p.name for p in (DEBIAN_DYNAMIC_RECONFIGURE / "templates").iterdir())
    assert names == sorted(p.name for p in KAME_TEMPLATES.glob("*.template"))
    for name in names:
        assert (KAME_TEMPLATES / name).read_bytes() == (DEBIAN_DYNAMIC_RECONFIGURE / "templates" / name).read_bytes()


@needs_debian
@pytest.mark.parametrize("which", ["Tutorials", "Edge"])
def test_cfg_run_with_catkins_arguments_writes_debians_bytes(tmp_path: Path, which: str) -> None:
    cfg = TUTORIAL_CFG
    if which == "Edge":
        cfg = tmp_path / "Edge.cfg"
        cfg.write_text(EDGE_CFG)
    debian = run_cfg(str(SYSTEM_PYTHON), cfg, tmp_path / "debian")
    kame = run_cfg(sys.executable, cfg, tmp_path / "kame")
    expected = {k: v for k, v in tree(tmp_path / "debian").items() if not k.startswith("cwd")}
    assert sorted(expected) == sorted([
        f"include/{which}Config.h", f"py/cfg/{which}Config.py", "py/cfg/__init__.py",
        f"share/docs/{which}Config-usage.dox", f"share/docs/{which}Config.dox", f"share/docs/{which}Config.wikidoc"])
    written = {k: v for k, v in tree(tmp_path / "kame").items() if not k.startswith("cwd")}
    for name, content in expected.items():
        assert written.get(name) == content, name
    assert sorted(written) == sorted(expected)
    assert kame.stdout.replace(str(tmp_path / "kame"), "OUT") == debian.stdout.replace(str(tmp_path / "debian"), "OUT")


def test_a_failing_cfg_exits_1_as_catkins(tmp_path: Path) -> None:
    cfg = tmp_path / "Bad.cfg"
    cfg.write_text(EDGE_CFG)
    (tmp_path / "include").write_text("a file where the header folder should be\n")
    args = [sys.executable, str(cfg), "x", str(tmp_path / "share"), str(tmp_path / "include"), str(tmp_path / "py")]
    result = subprocess.run(args, cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert result.returncode == 1
    assert "Error building srv Edge.srv" in result.stdout and "Traceback" in result.stderr


def tutorial_workspace(tmp_path: Path) -> tuple[Path, dict[str, str], Path]:
    """dynamic_tutorials in a workspace, its CMakeLists.txt as the tutorial's, with catkin_python_setup."""
    ws, env = make_workspace(tmp_path)
    pkg = ws / "src" / "dynamic_tutorials"
    shutil.copytree(TUTORIAL_PACKAGE, pkg)
    (pkg / "src" / "dynamic_tutorials").mkdir(parents=True)
    (pkg / "src" / "dynamic_tutorials" / "__init__.py").write_text("VALUE = 7\n")
    (pkg / "setup.py").write_text(textwrap.dedent("""\
        from setuptools import setup
        from catkin_pkg.python_setup import generate_distutils_setup

        setup(**generate_distutils_setup(packages=['dynamic_tutorials'], package_dir={'': 'src'}))
        """))
    (pkg / "CMakeLists.txt").write_text(textwrap.dedent("""\
        cmake_minimum_required(VERSION 3.0.2)
        project(dynamic_tutorials)
        find_package(catkin REQUIRED COMPONENTS rospy dynamic_reconfigure)
        catkin_python_setup()
        generate_dynamic_reconfigure_options(
          cfg/Tutorials.cfg
          # cfg/Commented.cfg
        )
        catkin_package()
        """))
    return ws, env, pkg


@needs_debian
def test_catkin_make_writes_catkins_files_and_python_imports_them(tmp_path: Path) -> None:
    ws, env, pkg = tutorial_workspace(tmp_path)
    result = run(["catkin_make"], ws, env)
    assert result.returncode == 0, result.stdout + result.stderr
    debian = tmp_path / "debian"
    run_cfg(str(SYSTEM_PYTHON), pkg / "cfg" / "Tutorials.cfg", debian)
    devel = ws / "devel"
    for ours, theirs in (("include/dynamic_tutorials/TutorialsConfig.h", "include/TutorialsConfig.h"),
                         ("lib/python3/dist-packages/dynamic_tutorials/cfg/TutorialsConfig.py",
                          "py/cfg/TutorialsConfig.py"),
                         ("lib/python3/dist-packages/dynamic_tutorials/cfg/__init__.py", "py/cfg/__init__.py"),
                         *((f"share/dynamic_tutorials/docs/{doc}", f"share/docs/{doc}") for doc in (
                             "TutorialsConfig.dox", "TutorialsConfig-usage.dox", "TutorialsConfig.wikidoc"))):
        assert (devel / ours).read_bytes() == (debian / theirs).read_bytes(), ours
    check = ("import dynamic_tutorials; from dynamic_tutorials.cfg import TutorialsConfig as C; "
             "print(dynamic_tutorials.VALUE, C.__file__, C.defaults['size'], C.max['speed'], C.Tutorials_Large)")
    out = bash(f"source {devel}/setup.bash && python -c \"{check}\"", env, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    module = devel / "lib/python3/dist-packages/dynamic_tutorials/cfg/TutorialsConfig.py"
    assert out.stdout.split() == ["7", str(module), "1", "inf", "2"]


def test_catkin_make_fails_a_package_whose_cfg_fails(tmp_path: Path) -> None:
    ws, env, pkg = tutorial_workspace(tmp_path)
    (pkg / "cfg" / "Tutorials.cfg").write_text(EDGE_CFG.replace('"Count", 3,', '"Count", "three",'))
    result = run(["catkin_make", "--no-color"], ws, env)
    assert result.returncode == 1
    assert ("kame: package 'dynamic_tutorials': Tutorials.cfg failed: TypeError: 'count' has type int, "
            "but default is 'three'") in result.stderr
    assert "Failed: dynamic_tutorials. The other packages were built" in result.stderr
    assert not (ws / "devel" / "include").exists()
