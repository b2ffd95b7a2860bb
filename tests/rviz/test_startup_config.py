"""What rviz opens with: a -d file that is not there is said so (rviz's ERROR line) and the default
layout opens; the tf tutorials' `rviz -d $(rospack find turtle_tf)/rviz/turtle_rviz.rviz` finds
its file, which shows the turtles' frames in the world frame."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from kame.catkin import executables
from kame.rviz.main import startup_config


def test_a_missing_file_is_said_so_and_the_default_layout_opens(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                                 capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setenv("NO_COLOR", "1")  # roscpp colours its lines otherwise
    missing = tmp_path / "turtle_rviz.rviz"
    config, path = startup_config(str(missing), "")
    assert path == ""
    assert [d.class_name for d in config.displays] == ["rviz/Grid"]
    err = capsys.readouterr().err
    assert err.startswith("[ERROR] [") and err.endswith(f"]: {missing} does not exist!\n"), err
    assert startup_config(str(missing), "odom")[0].fixed_frame == "odom"


@pytest.mark.parametrize("package", ["turtle_tf", "turtle_tf2"])
def test_the_tf_tutorials_rviz_file_is_shipped(package: str, capsys: pytest.CaptureFixture[str]) -> None:
    found = executables.packages(os.environ)[package]
    config, path = startup_config(str(found.path / "rviz" / "turtle_rviz.rviz"), "")
    assert path and capsys.readouterr().err == ""
    assert config.fixed_frame == "world"
    assert [d.class_name for d in config.displays] == ["rviz/Grid", "rviz/TF"]
