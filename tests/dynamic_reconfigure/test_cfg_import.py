"""`from <pkg>.cfg import <Name>Config` with no build step, equal to what catkin's generator makes."""

from __future__ import annotations

import importlib
import json
import math
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

import pytest

from kame.reconfigure.importer import CfgError, evaluate_cfg

HERE = Path(__file__).parent
TUTORIAL_PACKAGE = HERE / "dynamic_tutorials"
TUTORIAL_CFG = TUTORIAL_PACKAGE / "cfg" / "Tutorials.cfg"
SYSTEM_PYTHON = Path("/usr/bin/python3")


def debian_has_generator() -> bool:
    probe = [str(SYSTEM_PYTHON), "-c", "import dynamic_reconfigure.parameter_generator_catkin"]
    return SYSTEM_PYTHON.exists() and subprocess.run(probe, capture_output=True).returncode == 0


@pytest.fixture
def tutorials_config(monkeypatch: pytest.MonkeyPatch) -> Iterator[ModuleType]:
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(TUTORIAL_PACKAGE))
    yield importlib.import_module("dynamic_tutorials.cfg.TutorialsConfig")
    for name in [m for m in sys.modules if m == "dynamic_tutorials" or m.startswith("dynamic_tutorials.")]:
        del sys.modules[name]


def test_tutorial_config_imports_with_no_build(tutorials_config: ModuleType) -> None:
    from dynamic_tutorials.cfg import TutorialsConfig  # type: ignore[import-not-found]

    assert TutorialsConfig is tutorials_config
    assert TutorialsConfig.defaults == {"int_param": 50, "double_param": 0.5, "str_param": "Hello World",
                                        "bool_param": True, "size": 1, "speed": 1.0, "label": ""}
    assert TutorialsConfig.min["int_param"] == 0 and TutorialsConfig.max["int_param"] == 100
    assert TutorialsConfig.max["speed"] == math.inf and TutorialsConfig.min["label"] == ""
    assert TutorialsConfig.type == {"int_param": "int", "double_param": "double", "str_param": "str",
                                    "bool_param": "bool", "size": "int", "speed": "double", "label": "str"}
    assert TutorialsConfig.level["speed"] == 2 and TutorialsConfig.all_level == 6
    assert (TutorialsConfig.Tutorials_Small, TutorialsConfig.Tutorials_ExtraLarge) == (0, 3)
    inner = TutorialsConfig.config_description["groups"][0]["groups"][0]
    assert (inner["name"], inner["parent"], inner["field"], inner["class"]) == (
        "Inner_Most", 1, "DEFAULT::LIMITS::inner_most", "DEFAULT::LIMITS::INNER_MOST")


@pytest.mark.skipif(not debian_has_generator(), reason="Debian's python3-dynamic-reconfigure is not installed")
def test_description_equals_catkins_generator(tutorials_config: ModuleType) -> None:
    peer = HERE / "debian_cfg_peer.py"
    result = subprocess.run([str(SYSTEM_PYTHON), str(peer), str(TUTORIAL_CFG)], capture_output=True, text=True,
                            timeout=60)
    assert result.returncode == 0, result.stderr
    catkin = json.loads(result.stdout)
    # srcline and srcfile too: where the .cfg added each item, or where upstream's own module did
    assert tutorials_config.config_description == catkin["description"]
    constants = {k: v for k, v in vars(tutorials_config).items() if k.startswith("Tutorials_")}
    assert constants == catkin["constants"]


def test_a_bad_cfg_is_a_clear_import_error(tmp_path: Path) -> None:
    bad = tmp_path / "Bad.cfg"
    bad.write_text("from dynamic_reconfigure.parameter_generator_catkin import *\n"
                   "gen = ParameterGenerator()\ngen.add('x', str_t, 0, 'a string', 'a', max='z')\n")
    with pytest.raises(ValueError, match="Max or min specified for x"):
        evaluate_cfg(bad)
    bad.write_text("print('no generate call')\n")
    with pytest.raises(CfgError, match="called generate\\(\\) 0 times"):
        evaluate_cfg(bad)


def test_a_package_without_the_config_is_not_found(tutorials_config: ModuleType) -> None:
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module("dynamic_tutorials.cfg.MissingConfig")
