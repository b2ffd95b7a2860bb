"""rqt_graph on live graphs: the turtlesim lesson, mimic's two simulators, a dead and a hung node,
the window offscreen, `rqt_graph --output`, and Debian's real rosmaster with real rospy and roscpp
nodes beside a kame node."""

from __future__ import annotations

import subprocess
import time
import xml.etree.ElementTree as ET
import xmlrpc.client
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from kame.rqt.graph_model import GraphOptions, Kind, Mode, build_scene
from kame.rqt.graph_source import GraphSource
from tests.support import (
    SYSTEM_PYTHON,
    Proc,
    SilentPeer,
    free_port,
    have_debian_ros,
    ros_env,
    sending_to,
    wait_for_master,
)
from tests.turtlesim.sim import BIN, Sim, master, wait_until

SVG = "{http://www.w3.org/2000/svg}"
LESSON = [("/teleop_turtle", "/turtlesim", "/turtle1/cmd_vel")]


def start(sim: Sim, *args: str, stdin: int | None = None) -> Proc:
    proc = Proc([str(BIN / args[0]), *args[1:]], sim.env, cwd=sim.home, stdin=stdin)
    sim.procs.append(proc)
    return proc


@pytest.fixture(scope="module")
def lesson(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Sim]:
    """roscore's master and rosout, turtlesim and turtle_teleop_key (waiting for keys on a pipe)."""
    with master(tmp_path_factory.mktemp("rqt_graph")) as sim:
        start(sim, "rosout")
        start(sim, "rosrun", "turtlesim", "turtlesim_node", "--headless").wait_line("runs without a window")
        start(sim, "rosrun", "turtlesim", "turtle_teleop_key", stdin=subprocess.PIPE).wait_line("arrow keys")
        wait_until(lambda: bool(sending_to(sim.uri, "/teleop_turtle", "/turtle1/cmd_vel")), what="teleop's link")
        yield sim


@pytest.fixture
def source(lesson: Sim) -> Iterator[GraphSource]:
    graph = GraphSource(lesson.uri)
    yield graph
    graph.close()


def test_the_lessons_graph_in_each_mode(source: GraphSource) -> None:
    snap = source.fetch()
    assert snap.unreachable == frozenset()
    nodes_only = build_scene(snap, GraphOptions())
    assert nodes_only.names(Kind.NODE) == ["/teleop_turtle", "/turtlesim"]
    assert nodes_only.edge_names() == LESSON
    active = build_scene(snap, GraphOptions(mode=Mode.NODES_TOPICS_ACTIVE))
    assert active.names(Kind.TOPIC) == ["/turtle1/cmd_vel"]
    assert active.edge_names() == [("/teleop_turtle", "/turtle1/cmd_vel", ""), ("/turtle1/cmd_vel", "/turtlesim", "")]
    everything = build_scene(snap, GraphOptions(mode=Mode.NODES_TOPICS_ALL, hide_debug=False, hide_dead_sinks=False,
                                                hide_leaf_topics=False))
    assert {"/rosout", "/teleop_turtle", "/turtlesim"} == set(everything.names(Kind.NODE))
    assert {"/turtle1/cmd_vel", "/turtle1/pose", "/turtle1/color_sensor", "/rosout", "/rosout_agg"} <= set(
        everything.names(Kind.TOPIC))
    assert {("/turtlesim", "/turtle1/pose", ""), ("/turtlesim", "/rosout", ""), ("/rosout", "/rosout_agg", ""),
            ("/rosout", "/rosout", "")} <= set(everything.edge_names())  # rosout subscribes to /rosout
    assert not [t for t in everything.names(Kind.TOPIC) if "rotate_absolute" in t]  # ROS 1's turtlesim has no action


def test_rostopic_echo_appears_after_a_refresh(lesson: Sim, source: GraphSource) -> None:
    assert build_scene(source.fetch(), GraphOptions()).edge_names() == LESSON
    echo = start(lesson, "rostopic", "echo", "/turtle1/cmd_vel")
    try:
        def echo_edge() -> list[tuple[str, str, str]]:
            edges = build_scene(source.fetch(), GraphOptions()).edge_names()
            return [e for e in edges if e[1].startswith("/rostopic_")]

        wait_until(lambda: bool(echo_edge()), what="rostopic echo's connection in the graph")
        assert echo_edge()[0][0::2] == ("/teleop_turtle", "/turtle1/cmd_vel")
    finally:
        echo.stop()
    wait_until(lambda: build_scene(source.fetch(), GraphOptions()).edge_names() == LESSON, what="echo gone")


def test_output_svg_and_dot_from_the_command_line(lesson: Sim, tmp_path: Path) -> None:
    svg = tmp_path / "graph.svg"
    lesson.run("rqt_graph", "--output", str(svg), "--mode", "active")
    root = ET.parse(svg).getroot()
    shapes = {(g.get("class"), g.findtext(f"{SVG}title")) for g in root.iter(f"{SVG}g")}
    assert shapes == {("node", "/teleop_turtle"), ("node", "/turtlesim"), ("topic", "/turtle1/cmd_vel"),
                      ("edge", "/teleop_turtle->/turtle1/cmd_vel"), ("edge", "/turtle1/cmd_vel->/turtlesim"),
                      ("cluster", "/turtle1")}
    assert len(list(root.iter(f"{SVG}ellipse"))) == 2 and len(list(root.iter(f"{SVG}rect"))) == 3  # + background
    dot = tmp_path / "graph.dot"
    lesson.run("rosrun", "rqt_graph", "rqt_graph", "-o", str(dot), "__master:=" + lesson.uri)
    assert '"n:/teleop_turtle" -> "n:/turtlesim" [label="/turtle1/cmd_vel"];' in dot.read_text()
    png = tmp_path / "graph.png"
    lesson.run("rqt_graph", "--output", str(png), "--mode", "all", env=dict(lesson.env, QT_QPA_PLATFORM="offscreen"))
    assert png.read_bytes().startswith(b"\x89PNG")
    missing = lesson.run("rqt_graph", "-o", str(svg), env=dict(lesson.env, ROS_MASTER_URI=f"http://127.0.0.1:{free_port()}/"),
                         check=False)
    assert missing.returncode == 1 and "cannot reach the master" in missing.stderr


def test_a_dead_and_a_hung_node_leave_the_refresh_bounded(lesson: Sim) -> None:
    hung = SilentPeer()
    dead_uri = f"http://127.0.0.1:{free_port()}/"
    master = xmlrpc.client.ServerProxy(lesson.uri)
    master.registerSubscriber("/hung", "/turtle1/pose", "turtlesim/Pose", hung.uri)
    master.registerSubscriber("/dead", "/turtle1/pose", "turtlesim/Pose", dead_uri)
    graph = GraphSource(lesson.uri, node_timeout=0.5)
    try:
        started = time.monotonic()
        snap = graph.fetch()
        elapsed = time.monotonic() - started
        assert snap.unreachable == {"/hung", "/dead"}
        assert elapsed < graph.deadline + 1.0  # the hung node's call waits its timeout, never more
        scene = build_scene(snap, GraphOptions(mode=Mode.NODES_TOPICS_ALL))
        assert {v.name for v in scene.vertices if v.unreachable} == {"/hung", "/dead"}
        assert ("/turtlesim", "/turtle1/pose", "") in scene.edge_names()  # now two subscribers: not a leaf
        assert build_scene(snap, GraphOptions(hide_unreachable=True)).names(Kind.NODE) == ["/teleop_turtle",
                                                                                           "/turtlesim"]
    finally:
        graph.close()
        master.unregisterSubscriber("/hung", "/turtle1/pose", hung.uri)
        master.unregisterSubscriber("/dead", "/turtle1/pose", dead_uri)
        hung.close()


def test_a_hung_node_leaves_the_graph_window_responsive(lesson: Sim, qtbot) -> None:  # type: ignore[no-untyped-def]
    from PySide6.QtCore import QTimer

    from kame.rqt.graph_window import GraphWindow

    hung = SilentPeer()  # accepts the connection, never answers getBusInfo
    master = xmlrpc.client.ServerProxy(lesson.uri)
    master.registerSubscriber("/hung", "/turtle1/pose", "turtlesim/Pose", hung.uri)
    graph = GraphSource(lesson.uri, node_timeout=1.0)
    try:
        window = GraphWindow(graph.fetch)
        qtbot.addWidget(window)
        window.show()
        ticks = 0

        def tick() -> None:
            nonlocal ticks
            ticks += 1

        timer = QTimer()
        timer.timeout.connect(tick)
        timer.start(10)
        with qtbot.waitSignal(window.refreshed, timeout=10_000):
            window.refresh()
            assert not window.refresh_button.isEnabled()  # asked, not yet answered: the window goes on
        timer.stop()
        assert ticks >= 2  # the event loop kept running while the hung node's answer was awaited
        assert window.scene_model is not None and window.snapshot is not None
        assert window.snapshot.unreachable == {"/hung"} and window.refresh_button.isEnabled()
        window.mode_box.setCurrentIndex(list(Mode).index(Mode.NODES_TOPICS_ALL))
        assert {v.name for v in window.scene_model.vertices if v.unreachable} == {"/hung"}  # drawn red
    finally:
        graph.close()
        master.unregisterSubscriber("/hung", "/turtle1/pose", hung.uri)
        hung.close()


def shown_window(source: GraphSource, qtbot: Any) -> Any:
    """rqt_graph's window on the lesson's graph, shown and refreshed once."""
    from kame.rqt.graph_window import GraphWindow

    window = GraphWindow(source.fetch)
    qtbot.addWidget(window)
    window.show()
    with qtbot.waitSignal(window.refreshed, timeout=10_000):
        window.refresh()
    assert window.scene_model is not None and window.scene_model.edge_names() == LESSON
    return window


def test_the_window_draws_refreshes_and_highlights(lesson: Sim, source: GraphSource, qtbot, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    from PySide6.QtCore import QPoint

    window = shown_window(source, qtbot)
    assert "2 nodes, 0 topics, 1 edges" in window.status.text()
    window.mode_box.setCurrentIndex(list(Mode).index(Mode.NODES_TOPICS_ACTIVE))  # redraws from the same snapshot
    assert window.scene_model.names(Kind.TOPIC) == ["/turtle1/cmd_vel"]
    graphics = window.graphics
    assert graphics is not None
    item = graphics.vertex_items["t:/turtle1/cmd_vel"]
    shown = window.view.mapToScene(window.view.viewport().rect()).boundingRect()
    assert shown.contains(graphics.itemsBoundingRect())  # fitted after the change of mode, no Fit pressed
    centre = window.view.mapFromScene(item.sceneBoundingRect().center())
    qtbot.mouseMove(window.view.viewport(), QPoint(0, 0))
    qtbot.mouseMove(window.view.viewport(), centre)
    qtbot.waitUntil(lambda: graphics.highlighted == "t:/turtle1/cmd_vel", timeout=5_000)
    window.debug_box.setChecked(False)
    assert "/rosout" in window.scene_model.names(Kind.NODE)
    from kame.rqt.graph_window import save_drawing  # what the Save... dialog calls

    assert window.layout_model is not None
    save_drawing(tmp_path / "w.png", window.layout_model)
    assert (tmp_path / "w.png").stat().st_size > 0


def test_auto_refresh_shows_a_node_coming_and_going_by_itself(lesson: Sim, source: GraphSource, qtbot) -> None:  # type: ignore[no-untyped-def]
    """With Auto refresh on, the window's timer asks the graph again: rostopic echo's node appears,
    then leaves, with no refresh pressed; off, the timer stops."""
    window = shown_window(source, qtbot)
    assert not window.timer.isActive()  # off until the box is ticked, as in rqt_graph
    window.auto_period.setValue(1)
    window.auto_refresh.setChecked(True)

    def echoing() -> bool:
        return window.scene_model is not None and any(edge[1].startswith("/rostopic_")
                                                      for edge in window.scene_model.edge_names())

    echo = start(lesson, "rostopic", "echo", "/turtle1/cmd_vel")
    try:
        qtbot.waitUntil(echoing, timeout=60_000)
    finally:
        echo.stop()
    qtbot.waitUntil(lambda: not echoing(), timeout=60_000)
    assert window.scene_model.edge_names() == LESSON
    window.auto_refresh.setChecked(False)
    assert not window.timer.isActive()


def test_mimic_with_two_turtlesims(tmp_path: Path) -> None:
    """The lesson's question: with mimic between two simulators, how many nodes and edges?"""
    with master(tmp_path) as sim:
        for ns in ("turtlesim1", "turtlesim2"):
            start(sim, "rosrun", "turtlesim", "turtlesim_node", "--headless", f"__ns:={ns}", "__name:=sim")
        start(sim, "rosrun", "turtlesim", "mimic", "input:=turtlesim1/turtle1", "output:=turtlesim2/turtle1")
        graph = GraphSource(sim.uri)
        try:
            def scene(mode: Mode):  # type: ignore[no-untyped-def]
                return build_scene(graph.fetch(), GraphOptions(mode=mode))

            expected = [("/turtle_mimic", "/turtlesim2/sim", "/turtlesim2/turtle1/cmd_vel"),
                        ("/turtlesim1/sim", "/turtle_mimic", "/turtlesim1/turtle1/pose")]
            wait_until(lambda: scene(Mode.NODES_ONLY).edge_names() == expected, what="mimic's two links")
            nodes_only = scene(Mode.NODES_ONLY)
            assert (len(nodes_only.names(Kind.NODE)), len(nodes_only.edges)) == (3, 2)
            active = scene(Mode.NODES_TOPICS_ACTIVE)
            assert (len(active.names(Kind.NODE)), len(active.names(Kind.TOPIC)), len(active.edges)) == (3, 2, 4)
            assert {g.namespace for g in active.groups} == {"/turtlesim1", "/turtlesim1/turtle1", "/turtlesim2",
                                                            "/turtlesim2/turtle1"}
        finally:
            graph.close()


@pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 (rosmaster, rospy) is not installed")
def test_debian_rosmaster_with_real_rospy_and_roscpp_nodes_beside_kames(tmp_path: Path) -> None:
    from kame.node.node import Node, NodeConfig
    from std_msgs.msg import String
    from tests.support.roscpp import build_peers, roscpp_flags

    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = ros_env(tmp_path, uri)
    procs = [Proc([SYSTEM_PYTHON, "/usr/bin/rosmaster", "--core", "-p", str(port)], env)]
    kame_node: Node | None = None
    try:
        wait_for_master(uri, proc=procs[0])
        peer = Path(__file__).parents[1] / "interop" / "ros_peer_node.py"
        procs.append(Proc([SYSTEM_PYTHON, str(peer)], env))
        procs.append(Proc([SYSTEM_PYTHON, "/usr/bin/rostopic", "echo", "/chatter"], env))
        kame_node = Node(NodeConfig("/kame_listener", uri, "127.0.0.1", "127.0.0.1"))
        kame_node.subscribe("/chatter", "std_msgs/String", String._md5sum, String._full_text, lambda f, h: None)
        flags = roscpp_flags()  # roscpp's talker too where its headers are installed
        if flags is not None:
            procs.append(Proc([str(build_peers(flags)["talker"])], env))
        publishers = ["/peer"] + (["/cpp_talker"] if flags is not None else [])
        graph = GraphSource(uri)
        try:
            def links() -> list[tuple[str, str, str]]:
                return build_scene(graph.fetch(), GraphOptions()).edge_names()

            # each publisher to both subscribers: rospy's rostopic echo and kame's node
            wait_until(lambda: len(links()) == 2 * len(publishers), timeout=20, what="every link on /chatter")
            assert sorted((publisher, topic) for publisher, _, topic in links()) == sorted(
                (publisher, "/chatter") for publisher in publishers for _ in range(2))
            for publisher in publishers:
                subscribers = sorted(s for p, s, _ in links() if p == publisher)
                assert subscribers[0] == "/kame_listener" and subscribers[1].startswith("/rostopic_")
            # both ends report each connection (rospy's inbound row names the publisher by URI):
            # one link each, and every node, rospy, roscpp and kame, answered getBusInfo
            snap = graph.fetch()
            assert snap.unreachable == frozenset()
            assert len([link for link in snap.links if link.topic == "/chatter"]) == 2 * len(publishers)
        finally:
            graph.close()
    finally:
        if kame_node is not None:
            kame_node.shutdown("test over")
        for proc in reversed(procs):
            proc.stop()
