"""gzclient's window offscreen, with a stand-in for its ROS side: what arrives is drawn into the
status bar and the model, its buttons and menus ask for what Gazebo's do, and its bars fit."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import pytest

pytest.importorskip("PySide6", reason="kame[gui] is not installed")
pytest.importorskip("OpenGL", reason="kame[gui] (PyOpenGL) is not installed")

from PySide6.QtWidgets import QToolBar

from kame.gzclient import scene_message as sm
from kame.gzclient.model import ROTATE, SELECT, TRANSLATE, ModelMove
from kame.gzclient.source import Update
from kame.gzclient.window import GzClientWindow
from tests.gzclient.test_model import box_scene


@dataclass
class StandInSource:
    arriving: Update = field(default_factory=Update)
    asked: list[tuple[Any, ...]] = field(default_factory=list)

    def take(self) -> Update:
        update, self.arriving = self.arriving, Update()
        return update

    def set_paused(self, paused: bool) -> None:
        self.asked.append(("paused", paused))

    def step(self, iterations: int = 1) -> None:
        self.asked.append(("step", iterations))

    def reset_world(self) -> None:
        self.asked.append(("reset_world",))

    def reset_simulation(self) -> None:
        self.asked.append(("reset_simulation",))

    def move(self, move: ModelMove) -> None:
        self.asked.append(("move", move))

    def insert(self, shape: str, name: str, position: sm.Vector3) -> None:
        self.asked.append(("insert", shape, name))


@pytest.fixture
def window(qtbot: Any) -> tuple[GzClientWindow, StandInSource]:
    source = StandInSource()
    shown = GzClientWindow(source)
    qtbot.addWidget(shown)
    shown.resize(1024, 720)
    shown.show()
    return shown, source


def test_what_arrives_fills_the_status_bar_and_the_scene(window: tuple[GzClientWindow, StandInSource]) -> None:
    shown, source = window
    assert shown.windowTitle() == "Gazebo"
    assert shown.status_labels[0].text() == "Waiting for gzserver (/gazebo/kame/world_stats)"
    source.arriving = Update(scene=box_scene(), stats=sm.WorldStats(3.5, 4.0, 3500, False),
                             links={"red_box::link": ((0, 0, 0.5), (0, 0, 0, 1))},
                             models={"red_box": ((0, 0, 0.5), (0, 0, 0, 1))})
    shown.take()
    assert [label.text() for label in shown.status_labels][1:] == [
        "Sim Time: 00 00:00:03.500", "Real Time: 00 00:00:04.000", "Iterations: 3500"]
    assert shown.play_button.text() == "Pause" and not shown.step_button.isEnabled()
    assert shown.model.model_names() == ["ground_plane", "red_box"]
    assert any(batch.kind == "triangles" for batch in shown.view.scene.batches)
    source.arriving = Update(problems=["/gazebo/spawn_sdf_model: refused"])
    shown.take()
    assert shown.problem_label.text() == "/gazebo/spawn_sdf_model: refused"


def test_play_pause_step_and_the_resets(window: tuple[GzClientWindow, StandInSource]) -> None:
    shown, source = window
    source.arriving = Update(stats=sm.WorldStats(1.0, 1.0, 1000, False))
    shown.take()
    shown.play_button.click()
    source.arriving = Update(stats=sm.WorldStats(1.0, 1.2, 1000, True))
    shown.take()
    assert shown.play_button.text() == "Play" and shown.step_button.isEnabled()
    shown.step_button.click()
    shown.play_button.click()
    shown.reset_poses_action.trigger()
    shown.reset_world_action.trigger()
    assert source.asked == [("paused", True), ("step", 1), ("paused", False), ("reset_world",),
                            ("reset_simulation",)]


def test_modes_and_inserts(window: tuple[GzClientWindow, StandInSource]) -> None:
    shown, source = window
    source.arriving = Update(scene=box_scene(), models={"unit_box": ((3, 0, 0.5), (0, 0, 0, 1))})
    shown.take()
    for mode in (TRANSLATE, ROTATE, SELECT):
        shown.mode_actions[mode].trigger()
        assert shown.model.mode == mode
    shown.insert_actions["box"].trigger()
    shown.insert_actions["cylinder"].trigger()
    assert source.asked == [("insert", "box", "unit_box_0"), ("insert", "cylinder", "unit_cylinder")]


def test_the_bars_fit_a_small_window(window: tuple[GzClientWindow, StandInSource]) -> None:
    shown, source = window
    source.arriving = Update(stats=sm.WorldStats(86399.999, 86400.5, 86_399_999, False))
    shown.take()
    shown.resize(800, 600)
    for bar in shown.findChildren(QToolBar):
        assert bar.sizeHint().width() <= 800, f"the {bar.windowTitle()} bar is clipped"
