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

    def delete(self, model: str) -> None:
        self.asked.append(("delete", model))


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


def _drag(view: Any, button: Any, start: tuple[float, float], end: tuple[float, float], shift: bool = False) -> None:
    from PySide6.QtCore import QPoint, Qt
    from PySide6.QtTest import QTest

    held = Qt.KeyboardModifier.ShiftModifier if shift else Qt.KeyboardModifier.NoModifier
    QTest.mousePress(view, button, held, QPoint(round(start[0]), round(start[1])))
    for fraction in (0.25, 0.5, 0.75, 1.0):
        x, y = start[0] + fraction * (end[0] - start[0]), start[1] + fraction * (end[1] - start[1])
        QTest.mouseMove(view, QPoint(round(x), round(y)))
    QTest.mouseRelease(view, button, held, QPoint(round(end[0]), round(end[1])))


def test_the_mouse_as_gazebos(window: tuple[GzClientWindow, StandInSource], qtbot: Any) -> None:
    import numpy as np
    from PySide6.QtCore import Qt

    shown, source = window
    source.arriving = Update(scene=box_scene(), links={"red_box::link": ((0, 0, 0.5), (0, 0, 0, 1))},
                             models={"red_box": ((0, 0, 0.5), (0, 0, 0, 1))})
    shown.take()
    view, camera = shown.view, shown.view.camera
    qtbot.waitUntil(lambda: view.width() > 100)
    centre = (view.width() / 2, view.height() / 2)
    yaw, focal = camera.yaw, camera.focal_point.copy()
    _drag(view, Qt.MouseButton.MiddleButton, centre, (centre[0] + 100, centre[1]))
    assert camera.yaw != pytest.approx(yaw), "a middle drag orbits"
    eye, yaw = camera.eye().copy(), camera.yaw
    _drag(view, Qt.MouseButton.LeftButton, (50, 50), (150, 50))
    assert not np.allclose(camera.eye(), eye) and camera.yaw == pytest.approx(yaw), "a left drag pans"
    assert not np.allclose(camera.focal_point, focal)
    assert source.asked == [] and shown.model.selected is None  # drags on the ground move no model

    shown.mode_actions[TRANSLATE].trigger()
    box = camera.project(np.array([(0.0, 0.0, 0.5)]), view.width(), view.height())[0]
    _drag(view, Qt.MouseButton.LeftButton, (box[0], box[1]), (box[0] + 40, box[1] + 20))
    moves = [asked[1] for asked in source.asked if asked[0] == "move"]
    assert moves and all(move.model == "red_box" for move in moves)
    assert moves[-1].position[2] == pytest.approx(0.5) and moves[-1].position[:2] != pytest.approx((0, 0))
    assert shown.model.selected == "red_box"
    shown.delete_action.trigger()
    assert source.asked[-1] == ("delete", "red_box") and shown.model.selected is None
    shown.delete_action.trigger()  # nothing selected: nothing asked
    assert source.asked[-1] == ("delete", "red_box")
