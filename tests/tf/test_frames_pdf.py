"""frames.pdf's edge labels never meet: the tf tutorial's world -> turtle1 and world -> turtle2
(one parent, two children side by side, five lines each) and a wider tree; each block stands
over its child's column when nothing is in its way."""

from __future__ import annotations

import pytest

from kame.tf.frames_pdf import Edge, _layout, label_boxes, render


def _label(broadcaster: str) -> tuple[str, ...]:  # the lines view_frames writes
    return (f"Broadcaster: {broadcaster}", "Average rate: 62.706", "Buffer length: 4.976",
            "Most recent transform: 1795930221.970", "Oldest transform: 1795930216.994")


def _no_two_meet(edges: list[Edge]) -> None:
    boxes = list(label_boxes(edges).values())
    assert len(boxes) == len(edges)
    for i, box in enumerate(boxes):
        assert not any(box.meets(other) for other in boxes[i + 1:]), (box, boxes)


def test_the_tutorials_two_turtles() -> None:
    edges = [Edge("world", "turtle1", _label("/turtle1_tf2_broadcaster")),
             Edge("world", "turtle2", _label("/turtle2_tf2_broadcaster"))]
    _no_two_meet(edges)
    boxes = label_boxes(edges)
    columns = _layout(edges)[0]
    for index, edge in enumerate(edges):  # nothing moved: each over its own turtle
        assert boxes[index].x + boxes[index].w / 2 == pytest.approx(columns[edge.child][0])
    assert render(edges, ["view_frames Result"]).startswith(b"%PDF-1.4")


def test_a_wide_tree_and_a_lone_edge() -> None:
    edges = [Edge("map", "odom", _label("/amcl")), Edge("odom", "base_footprint", _label("/stageros")),
             *(Edge("base_footprint", f"link_{i}", _label("/robot_state_publisher")) for i in range(6)),
             *(Edge(f"link_{i}", f"sensor_{i}", _label("/robot_state_publisher")) for i in range(6)),
             Edge("world", "turtle1", _label("/turtle1_tf2_broadcaster")),
             Edge("turtle1", "carrot1", _label("/fixed_tf2_broadcaster"))]
    _no_two_meet(edges)
    alone = [Edge("world", "turtle1", _label("/a"))]
    box = label_boxes(alone)[0]
    x = _layout(alone)[0]["turtle1"][0]
    assert box.x + box.w / 2 == pytest.approx(x)  # over its child
