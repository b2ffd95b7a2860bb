"""gzclient's model without a window: the scene message both ways, the scene drawn from a world's
visuals and link poses, a model picked by the ray through a pixel, translate and rotate drags as
set_model_state values, Gazebo's mouse on the camera, the status bar's figures."""

from __future__ import annotations

import importlib.util
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from kame.gzclient import scene_message as sm
from kame.gzclient.model import (
    ORBIT,
    PAN,
    ROTATE,
    TRANSLATE,
    ZOOM,
    ClientModel,
    drag_action,
    focus_on,
    unique_name,
    view_ray,
)
from kame.gzclient.status import StatusFigures, gazebo_time

DATA = Path(__file__).resolve().parent / "data"
WIDTH, HEIGHT = 800, 600
RED = (1.0, 0.0, 0.0, 1.0)  # Gazebo/Red, as kame.gazebo.materials gives it


def box_scene(generation: int = 1) -> sm.SceneMessage:
    ground = sm.VisualMessage("ground_plane::link", "visual", "plane", (100.0, 100.0), (0, 0, 0), (0, 0, 0, 1),
                              (0.7, 0.7, 0.7, 1.0), None)
    box = sm.VisualMessage("red_box::link", "visual", "box", (1.0, 1.0, 1.0), (0, 0, 0), (0, 0, 0, 1), RED, None)
    sun = sm.LightMessage("sun", "directional", (0, 0, 10), (0, 0, 0, 1), (0.8, 0.8, 0.8, 1), (-0.5, 0.1, -0.9))
    return sm.SceneMessage("default", generation, (0.7, 0.7, 0.7, 1), (0.4, 0.4, 0.4, 1), (sun,), (ground, box))


def box_model() -> ClientModel:
    model = ClientModel()
    model.set_scene(box_scene())
    model.set_link_poses({"ground_plane::link": ((0, 0, 0), (0, 0, 0, 1)),
                          "red_box::link": ((0, 0, 0.5), (0, 0, 0, 1))})
    model.set_model_poses({"ground_plane": ((0, 0, 0), (0, 0, 0, 1)), "red_box": ((0, 0, 0.5), (0, 0, 0, 1))})
    return model


def ray_at(model: ClientModel, point: tuple[float, float, float]) -> tuple[np.ndarray, np.ndarray]:
    x, y = model.camera.project(np.array([point]), WIDTH, HEIGHT)[0]
    return view_ray(model.camera, x, y, WIDTH, HEIGHT)


def test_the_scene_message_round_trips_with_a_mesh() -> None:
    triangles = np.arange(18, dtype=np.float32).reshape(6, 3)
    mesh = sm.VisualMessage("robot::base", "body", "mesh", (), (1, 2, 3), (0, 0, 0, 1), (0.1, 0.2, 0.3, 1), triangles)
    scene = box_scene()
    scene = sm.SceneMessage(scene.world, 7, scene.background, scene.ambient, scene.lights, (*scene.visuals, mesh))
    back = sm.decode_scene(sm.encode_scene(scene))
    assert back.generation == 7 and back.lights == scene.lights
    assert [v.link for v in back.visuals] == ["ground_plane::link", "red_box::link", "robot::base"]
    assert back.visuals[2].triangles is not None and np.array_equal(back.visuals[2].triangles, triangles)
    assert back.visuals[2].model == "robot"


@pytest.mark.parametrize("text", ["{}", "[]", "not json", '{"format": 1, "world": "w"}',
                                  '{"format": 1, "world": "w", "generation": 1, "background": [1, 1],'
                                  ' "ambient": [0, 0, 0, 1], "lights": [], "visuals": []}'])
def test_a_message_that_is_not_a_scene_is_refused_with_a_reason(text: str) -> None:
    with pytest.raises(sm.SceneMessageError):
        sm.decode_scene(text)


def test_stats_round_trip_and_bad_stats_are_refused() -> None:
    stats = sm.WorldStats(12.5, 13.0, 12500, False)
    assert sm.decode_stats(sm.encode_stats(stats)) == stats
    paused = sm.WorldStats(12.5, 13.0, 12500, True, {"m::l": ((1.0, 2.0, 3.0), (0.0, 0.0, 0.0, 1.0))},
                           {"m": ((1.0, 2.0, 3.0), (0.0, 0.0, 0.0, 1.0))})
    assert sm.decode_stats(sm.encode_stats(paused)) == paused
    with pytest.raises(sm.SceneMessageError):
        sm.decode_stats('{"sim_time": "soon"}')


# MuJoCo runs in a child: loaded here it would fix this process's PyOpenGL to EGL, and the rviz
# and gzclient windows later tests draw in this process would find no context of Qt's
WORLD_SCENE = """
import json, sys
from kame.gazebo.world import World
from kame.gazebo_ros.client_feed import scene_of
from kame.gzclient.scene_message import encode_scene
world = World.from_file(sys.argv[1])
links = {link: [*state.pose.position, *state.pose.orientation] for link, state in world.link_states().items()}
print(json.dumps({"scene": encode_scene(scene_of(world)), "links": links}))
"""


def test_a_worlds_visuals_become_the_scene_gzclient_draws() -> None:
    if importlib.util.find_spec("mujoco") is None:
        pytest.skip("kame[gazebo] (MuJoCo) is not installed")
    out = subprocess.run([sys.executable, "-c", WORLD_SCENE, str(DATA / "red_box.world")], capture_output=True,
                         text=True, timeout=120, check=True).stdout
    sent = json.loads(out.splitlines()[-1])
    message = sm.decode_scene(sent["scene"])
    assert {v.model for v in message.visuals} == {"ground_plane", "red_box"}
    assert [light.name for light in message.lights] == ["sun"]
    model = ClientModel()
    model.set_scene(message)
    model.set_link_poses({link: ((x, y, z), (qx, qy, qz, qw))
                          for link, (x, y, z, qx, qy, qz, qw) in sent["links"].items()})
    scene = model.render()
    triangles = [b for b in scene.batches if b.kind == "triangles"]
    corners = np.concatenate([b.vertices[np.isclose(b.float_colors(), RED, atol=0.05).all(axis=1)] for b in triangles])
    assert len(corners) == 36, "the red box is drawn"
    assert corners[:, 2].min() == pytest.approx(0.0, abs=0.01) and corners[:, 2].max() == pytest.approx(1.0, abs=0.01)
    assert model.pick(*ray_at(model, (0.0, 0.0, 0.5))) == "red_box"


def test_the_scene_is_the_same_object_until_poses_or_selection_change() -> None:
    model = box_model()
    first = model.render()
    assert model.render() is first
    model.select("red_box")
    second = model.render()
    assert second is not first
    white = [b.vertices[np.isclose(b.float_colors(), 1.0).all(axis=1)] for b in second.batches if b.kind == "lines"]
    assert sum(len(lines) for lines in white) == 24  # the selected box's outline: 12 edges
    model.set_link_poses({"red_box::link": ((2, 0, 0.5), (0, 0, 0, 1))})
    assert model.render() is not second


def test_the_world_lights_as_opengl_takes_them() -> None:
    model = box_model()
    assert model.drawn_models() == ["ground_plane", "red_box"]
    (sun,) = model.lights
    towards = np.array([0.5, -0.1, 0.9]) / np.linalg.norm([0.5, -0.1, 0.9])
    assert sun.position == pytest.approx((*towards, 0.0)) and sun.diffuse == (0.8, 0.8, 0.8, 1)


def test_a_link_moves_its_visuals() -> None:
    model = box_model()
    model.set_link_poses({"red_box::link": ((3.0, -1.0, 0.5), (0, 0, 0, 1))})
    vertices = np.concatenate([b.vertices for b in model.render().batches if b.kind == "triangles"])
    assert vertices[:, 0].max() == pytest.approx(3.5) and vertices[:, 1].min() == pytest.approx(-1.5)


def test_a_click_on_the_box_picks_it_and_one_on_the_ground_picks_nothing() -> None:
    model = box_model()
    assert model.pick(*ray_at(model, (0.0, 0.0, 0.5))) == "red_box"
    assert model.pick(*ray_at(model, (3.0, 3.0, 0.0))) is None  # the ground plane is never picked
    model.mode = TRANSLATE
    assert model.press(*ray_at(model, (3.0, 3.0, 0.0))) is False and model.selected is None


def test_translate_drags_the_model_over_the_plane_through_its_origin() -> None:
    model = box_model()
    model.mode = TRANSLATE
    assert model.press(*ray_at(model, (0.0, 0.0, 0.5))) is True
    assert model.selected == "red_box" and model.dragging
    move = model.drag(*ray_at(model, (1.0, 0.5, 0.5)))
    assert move is not None and move.model == "red_box"
    assert move.position == pytest.approx((1.0, 0.5, 0.5), abs=1e-6)
    assert move.orientation == pytest.approx((0, 0, 0, 1))
    model.release()
    assert not model.dragging and model.drag(*ray_at(model, (2.0, 0.0, 0.5))) is None


def test_rotate_turns_the_model_about_the_vertical_through_its_origin() -> None:
    model = box_model()
    model.set_model_poses({"red_box": ((0, 0, 0.5), (0, 0, math.sin(0.25), math.cos(0.25)))})  # yaw 0.5 rad
    model.set_link_poses({"red_box::link": ((0, 0, 0.5), (0, 0, math.sin(0.25), math.cos(0.25)))})
    model.mode = ROTATE
    assert model.press(*ray_at(model, (0.3, 0.0, 0.5)))  # on the box's near face, right of its centre
    grabbed = model._drag.grabbed if model._drag is not None else None
    assert grabbed is not None
    angle = math.atan2(grabbed[1], grabbed[0]) + math.pi / 2
    reach = float(np.hypot(grabbed[0], grabbed[1]))
    move = model.drag(*ray_at(model, (reach * math.cos(angle), reach * math.sin(angle), 0.5)))
    assert move is not None and move.position == (0, 0, 0.5)
    x, y, z, w = move.orientation
    assert (x, y) == pytest.approx((0, 0), abs=1e-9)
    assert 2 * math.atan2(z, w) == pytest.approx(0.5 + math.pi / 2, abs=1e-6)


def test_gazebos_mouse_on_the_camera() -> None:
    assert drag_action(left=True, middle=False, right=False, shift=False) == PAN
    assert drag_action(left=False, middle=True, right=False, shift=False) == ORBIT
    assert drag_action(left=True, middle=False, right=False, shift=True) == ORBIT
    assert drag_action(left=False, middle=False, right=True, shift=False) == ZOOM
    assert drag_action(left=False, middle=False, right=False, shift=False) is None
    camera = ClientModel().camera
    assert camera.eye() == pytest.approx((5.0, -5.0, 2.0))  # gzclient's first view


def test_orbit_and_wheel_turn_about_the_point_under_the_mouse_without_moving_the_eye() -> None:
    model = box_model()
    point = model.surface_point(*ray_at(model, (0.0, 0.0, 1.0)))  # the box's top face
    assert point is not None and point[2] == pytest.approx(1.0, abs=1e-6)
    ground = model.surface_point(*ray_at(model, (2.0, 1.0, 0.0)))
    assert ground == pytest.approx((2.0, 1.0, 0.0), abs=1e-6)
    eye = model.camera.eye()
    focus_on(model.camera, point)
    assert model.camera.eye() == pytest.approx(eye) and model.camera.focal_point == pytest.approx(point)


def test_inserted_shapes_are_named_as_gazebo_names_them_and_stand_where_the_view_looks() -> None:
    assert unique_name("unit_box", ["ground_plane"]) == "unit_box"
    assert unique_name("unit_box", ["unit_box", "unit_box_0"]) == "unit_box_1"
    model = ClientModel()
    assert model.insert_point(WIDTH, HEIGHT) == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)


def test_the_status_bar_in_gazebos_words() -> None:
    assert gazebo_time(0) == "00 00:00:00.000"
    assert gazebo_time(90061.5) == "01 01:01:01.500"
    status = StatusFigures()
    assert status.fields() == ["Waiting for gzserver (/gazebo/kame/world_stats)"]
    for tick in range(11):
        status.update(sm.WorldStats(0.5 * tick * 0.2, tick * 0.2, 500 * tick, False))  # half real time
    assert status.real_time_factor == pytest.approx(0.5)
    assert status.fields() == ["Real Time Factor: 0.50", "Sim Time: 00 00:00:01.000", "Real Time: 00 00:00:02.000",
                               "Iterations: 5000"]
    status.update(sm.WorldStats(0.0, 0.0, 0, True))  # reset_simulation
    assert status.paused and status.real_time_factor == 0.0
