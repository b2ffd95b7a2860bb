"""rqt_graph's model, layout and file writers, without a window or a network."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import pytest

from kame.rqt.graph_export import to_dot, to_svg
from kame.rqt.graph_layout import layout
from kame.rqt.graph_model import GraphOptions, Kind, Link, Mode, NameFilter, build_scene, node_id, snapshot_from

SVG = "{http://www.w3.org/2000/svg}"

# the turtlesim lesson with rosout, as getSystemState and getBusInfo answer it
STATE = [
    [["/turtle1/cmd_vel", ["/teleop_turtle"]], ["/turtle1/pose", ["/turtlesim"]],
     ["/rosout", ["/turtlesim", "/teleop_turtle"]], ["/rosout_agg", ["/rosout"]]],
    [["/turtle1/cmd_vel", ["/turtlesim"]], ["/rosout", ["/rosout"]], ["/turtle1/rotate_absolute/goal", ["/turtlesim"]]],
    [["/spawn", ["/turtlesim"]], ["/rosout/get_loggers", ["/rosout"]]],
]
URIS = {"/teleop_turtle": "http://127.0.0.1:4001/", "/turtlesim": "http://127.0.0.1:4002/",
        "/rosout": "http://127.0.0.1:4003/"}
BUS = {
    "/teleop_turtle": [[1, "/turtlesim", "o", "TCPROS", "/turtle1/cmd_vel", True, "..."],
                       [2, "/rosout", "o", "TCPROS", "/rosout", True]],
    # inbound rows name the publisher by URI (rospy and roscpp alike); an unconnected row is ignored
    "/turtlesim": [[3, "http://127.0.0.1:4001", "i", "TCPROS", "/turtle1/cmd_vel", True],
                   [4, "http://127.0.0.1:9999/", "i", "TCPROS", "/turtle1/cmd_vel", False],
                   [5, "/rosout", "o", "TCPROS", "/rosout", 1]],
    "/rosout": [[6, "http://127.0.0.1:4001/", "i", "TCPROS", "/rosout", True]],
}


def snapshot(bus: dict | None = None):  # type: ignore[no-untyped-def]
    return snapshot_from(STATE, BUS if bus is None else bus, URIS)


def test_links_come_from_both_ends_of_each_connection() -> None:
    snap = snapshot()
    assert sorted(snap.links) == [Link("/teleop_turtle", "/rosout", "/rosout"),
                                  Link("/teleop_turtle", "/turtlesim", "/turtle1/cmd_vel"),
                                  Link("/turtlesim", "/rosout", "/rosout")]
    assert snap.unreachable == frozenset()
    assert snapshot({**BUS, "/rosout": None}).unreachable == {"/rosout"}


def test_nodes_only_is_the_lessons_picture() -> None:
    scene = build_scene(snapshot(), GraphOptions())
    assert scene.names(Kind.NODE) == ["/teleop_turtle", "/turtlesim"]  # /rosout is debug
    assert scene.names(Kind.TOPIC) == []
    assert scene.edge_names() == [("/teleop_turtle", "/turtlesim", "/turtle1/cmd_vel")]
    shown = build_scene(snapshot(), GraphOptions(hide_debug=False))
    assert shown.names(Kind.NODE) == ["/rosout", "/teleop_turtle", "/turtlesim"]
    assert len(shown.edges) == 3


def test_active_and_all_topics() -> None:
    active = build_scene(snapshot(), GraphOptions(mode=Mode.NODES_TOPICS_ACTIVE))
    assert active.names(Kind.TOPIC) == ["/turtle1/cmd_vel"]
    assert active.edge_names() == [("/teleop_turtle", "/turtle1/cmd_vel", ""), ("/turtle1/cmd_vel", "/turtlesim", "")]
    everything = GraphOptions(mode=Mode.NODES_TOPICS_ALL, hide_dead_sinks=False, hide_leaf_topics=False)
    scene = build_scene(snapshot(), everything)
    assert scene.names(Kind.TOPIC) == ["/turtle1/cmd_vel", "/turtle1/pose", "/turtle1/rotate_absolute/goal"]
    assert ("/turtlesim", "/turtle1/pose", "") in scene.edge_names()
    assert ("/turtle1/rotate_absolute/goal", "/turtlesim", "") in scene.edge_names()
    # dead sinks: published, never subscribed; leaf topics: one node only
    no_sinks = build_scene(snapshot(), GraphOptions(mode=Mode.NODES_TOPICS_ALL, hide_leaf_topics=False))
    assert no_sinks.names(Kind.TOPIC) == ["/turtle1/cmd_vel", "/turtle1/rotate_absolute/goal"]
    no_leaves = build_scene(snapshot(), GraphOptions(mode=Mode.NODES_TOPICS_ALL, hide_dead_sinks=False))
    assert no_leaves.names(Kind.TOPIC) == ["/turtle1/cmd_vel"]
    debug = build_scene(snapshot(), GraphOptions(mode=Mode.NODES_TOPICS_ALL, hide_debug=False))
    assert "/rosout" in debug.names(Kind.TOPIC) and "/rosout_agg" not in debug.names(Kind.TOPIC)  # a dead sink


def test_filters_groups_and_unreachable() -> None:
    assert NameFilter("turtle, -teleop")("/turtlesim") and not NameFilter("turtle, -teleop")("/teleop_turtle")
    assert NameFilter("([")("/a([b")  # a bad expression matches literally
    scene = build_scene(snapshot(), GraphOptions(node_filter="-teleop"))
    assert scene.names(Kind.NODE) == ["/turtlesim"] and scene.edges == ()
    topics = build_scene(snapshot(), GraphOptions(mode=Mode.NODES_TOPICS_ALL, topic_filter="-cmd_vel",
                                                  hide_leaf_topics=False))
    assert topics.names(Kind.TOPIC) == ["/turtle1/rotate_absolute/goal"]
    grouped = build_scene(snapshot(), GraphOptions(mode=Mode.NODES_TOPICS_ACTIVE))
    assert [(g.namespace, g.members) for g in grouped.groups] == [("/turtle1", ("t:/turtle1/cmd_vel",))]
    assert build_scene(snapshot(), GraphOptions(mode=Mode.NODES_TOPICS_ACTIVE, group_namespaces=False)).groups == ()
    dead = snapshot({**BUS, "/turtlesim": None})
    shown = build_scene(dead, GraphOptions())
    assert shown.vertex(node_id("/turtlesim")).unreachable
    assert shown.edge_names() == [("/teleop_turtle", "/turtlesim", "/turtle1/cmd_vel")]  # teleop still says so
    assert build_scene(dead, GraphOptions(hide_unreachable=True)).names(Kind.NODE) == ["/teleop_turtle"]


def test_hovering_highlights_the_neighbourhood() -> None:
    scene = build_scene(snapshot(), GraphOptions(mode=Mode.NODES_TOPICS_ACTIVE))
    vertices, edges = scene.neighbourhood("t:/turtle1/cmd_vel")
    assert vertices == {"t:/turtle1/cmd_vel", "n:/teleop_turtle", "n:/turtlesim"} and len(edges) == 2
    assert scene.neighbourhood("n:/teleop_turtle")[0] == {"n:/teleop_turtle", "t:/turtle1/cmd_vel"}


def _overlap(a, b) -> bool:  # type: ignore[no-untyped-def]
    return a.x < b.x + b.w and b.x < a.x + a.w and a.y < b.y + b.h and b.y < a.y + a.h


@pytest.mark.parametrize("mode", list(Mode))
def test_layout_runs_left_to_right_without_overlaps(mode: Mode) -> None:
    options = GraphOptions(mode=mode, hide_debug=False, hide_dead_sinks=False, hide_leaf_topics=False)
    scene = build_scene(snapshot(), options)
    drawn = layout(scene)
    boxes = list(drawn.boxes.values())
    assert len(boxes) == len(scene.vertices)
    assert not any(_overlap(a, b) for i, a in enumerate(boxes) for b in boxes[i + 1:])
    for index, edge in enumerate(scene.edges):
        if edge.source != edge.target:
            assert drawn.boxes[edge.source].centre[0] != drawn.boxes[edge.target].centre[0]
        path = drawn.paths[index]
        assert all(0 <= x <= drawn.width and 0 <= y <= drawn.height for x, y in path)
    for group in scene.groups:  # one frame a namespace, holding its members and no other vertex
        frame = drawn.groups[group.namespace]
        assert not any(_overlap(frame, box) for vid, box in drawn.boxes.items() if vid not in group.members)
        assert all(_overlap(frame, drawn.boxes[member]) for member in group.members)
    publisher, topic = drawn.boxes["n:/teleop_turtle"], drawn.boxes.get("t:/turtle1/cmd_vel")
    if topic is not None:
        assert publisher.centre[0] < topic.centre[0] < drawn.boxes["n:/turtlesim"].centre[0]


def test_an_empty_graph_and_a_self_loop_lay_out() -> None:
    empty = build_scene(snapshot_from([[], [], []], {}, {}), GraphOptions())
    assert layout(empty).boxes == {}
    loop = snapshot_from([[["/echo", ["/a"]]], [["/echo", ["/a"]]], []],
                         {"/a": [[1, "/a", "o", "TCPROS", "/echo", True]]}, {"/a": "http://h:1/"})
    scene = build_scene(loop, GraphOptions())
    assert scene.edge_names() == [("/a", "/a", "/echo")]
    assert len(layout(scene).paths[0]) == 4


def test_svg_and_dot_name_every_shape() -> None:
    scene = build_scene(snapshot(), GraphOptions(mode=Mode.NODES_TOPICS_ACTIVE))
    root = ET.fromstring(to_svg(layout(scene)))
    titles = {kind: sorted(g.findtext(f"{SVG}title") or "" for g in root.iter(f"{SVG}g") if g.get("class") == kind)
              for kind in ("node", "topic", "edge", "cluster")}
    assert titles == {"node": ["/teleop_turtle", "/turtlesim"], "topic": ["/turtle1/cmd_vel"],
                      "edge": ["/teleop_turtle->/turtle1/cmd_vel", "/turtle1/cmd_vel->/turtlesim"],
                      "cluster": ["/turtle1"]}
    assert len(list(root.iter(f"{SVG}ellipse"))) == 2
    dot = to_dot(scene)
    assert '"t:/turtle1/cmd_vel" [label="/turtle1/cmd_vel", shape=box];' in dot
    assert '"n:/teleop_turtle" -> "t:/turtle1/cmd_vel";' in dot and "subgraph cluster_0" in dot
    labelled = to_dot(build_scene(snapshot(), GraphOptions()))
    assert '"n:/teleop_turtle" -> "n:/turtlesim" [label="/turtle1/cmd_vel"];' in labelled


def test_group_actions_draws_an_actions_five_topics_as_one_box() -> None:
    action = "/turtle1/rotate_absolute"
    client_side, server_side = ("goal", "cancel"), ("status", "feedback", "result")
    state = [
        [[f"{action}/{t}", ["/teleop"]] for t in client_side] + [[f"{action}/{t}", ["/turtlesim"]] for t in server_side]
        + [["/turtle1/pose", ["/turtlesim"]], ["/half/goal", ["/teleop"]]],
        [[f"{action}/{t}", ["/turtlesim"]] for t in client_side] + [[f"{action}/{t}", ["/teleop"]] for t in server_side]
        + [["/turtle1/pose", ["/teleop"]], ["/half/goal", ["/turtlesim"]]],
        [],
    ]
    snap = snapshot_from(state, {}, {})
    plain = build_scene(snap, GraphOptions(mode=Mode.NODES_TOPICS_ALL))
    assert f"{action}/feedback" in plain.names(Kind.TOPIC)
    grouped = build_scene(snap, GraphOptions(mode=Mode.NODES_TOPICS_ALL, group_actions=True))
    box = f"{action}/action_topics"
    assert grouped.names(Kind.TOPIC) == ["/half/goal", "/turtle1/pose", box]  # /half is not a whole action
    assert {e for e in grouped.edge_names() if box in e} == {
        ("/teleop", box, ""), ("/turtlesim", box, ""), (box, "/teleop", ""), (box, "/turtlesim", "")}
