"""rqt_graph's layout of the courses' graphs stays readable: two topics between one pair of
nodes, either way round, are two curves apart, each with its own label, and no two labels'
boxes meet (nor a label and a node), in nodes-only mode (the default, which labels each edge
with its topic) and with topics drawn."""

from __future__ import annotations

import math

import pytest

from kame.rqt.graph_layout import TWIN_GAP, Box, layout
from kame.rqt.graph_model import GraphOptions, Mode, build_scene
from tests.rqt.course_graphs import COURSES, DRAW_SQUARE, course_snapshot


def _meet(a: Box, b: Box) -> bool:
    return a.x < b.x + b.w and b.x < a.x + a.w and a.y < b.y + b.h and b.y < a.y + a.h


@pytest.mark.parametrize("mode", list(Mode))
@pytest.mark.parametrize("course", sorted(COURSES))
def test_no_two_labels_meet(course: str, mode: Mode) -> None:
    scene = build_scene(course_snapshot(COURSES[course]), GraphOptions(mode=mode))
    drawn = layout(scene)
    assert sorted(drawn.labels) == [i for i, e in enumerate(scene.edges) if e.label]
    labels = list(drawn.labels.values())
    for i, label in enumerate(labels):
        assert not any(_meet(label, other) for other in labels[i + 1:]), course
        assert not any(_meet(label, box) for box in drawn.boxes.values()), course
        assert label.x >= 0 and label.y >= 0
        assert label.x + label.w <= drawn.width and label.y + label.h <= drawn.height


def test_two_topics_between_two_nodes_either_way_are_two_curves() -> None:
    scene = build_scene(course_snapshot(DRAW_SQUARE), GraphOptions())
    assert sorted(scene.edge_names()) == [("/draw_square", "/turtlesim", "/turtle1/cmd_vel"),
                                          ("/turtlesim", "/draw_square", "/turtle1/pose")]
    drawn = layout(scene)
    middles = [path[len(path) // 2] for path in drawn.paths]
    assert math.dist(*middles) >= TWIN_GAP - 1
