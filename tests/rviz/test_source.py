"""rviz's node on a live master: messages arriving faster than the window draws are coalesced
(the newest scan wins; marker messages are all kept, in order), each woken once, tf lookups go
through the Buffer, and the tools' publishers reach a subscriber."""

from __future__ import annotations

import threading
import time
import xmlrpc.client
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from geometry_msgs.msg import Point, Pose, TransformStamped
from kame.node.node import Node, NodeConfig
from kame.node.topics import serialize_frame
from kame.rostime import Duration, Time
from kame.rviz.source import RvizSource
from sensor_msgs.msg import LaserScan
from tests.tf.graph import Graph
from visualization_msgs.msg import Marker, MarkerArray


@contextmanager
def rviz_with(tmp_path: Path, peer: str, on_ready: Callable[[], None], sim_time: bool = False,
              ) -> Iterator[tuple[RvizSource, Node]]:
    """rviz's source on a node of its own and a peer node (named `peer`) on a fresh master,
    all stopped at the end."""
    graph = Graph(tmp_path)
    if sim_time:
        xmlrpc.client.ServerProxy(graph.uri).setParam("/test", "/use_sim_time", True)
    rviz = Node(NodeConfig("/rviz_source_test", graph.uri, "127.0.0.1", "127.0.0.1"))
    other = Node(NodeConfig(peer, graph.uri, "127.0.0.1", "127.0.0.1"))
    source = RvizSource(rviz, on_ready)
    try:
        yield source, other
    finally:
        source.close()
        other.shutdown("test over")
        rviz.shutdown("test over")
        graph.stop()


def test_a_burst_of_scans_is_one_message_and_markers_are_each_kept(tmp_path: Path) -> None:
    woken = threading.Event()
    with rviz_with(tmp_path, "/talker", woken.set) as (source, talker):
        assert source.watch("/scan", "sensor_msgs/LaserScan", keep_every=False) == ""
        assert source.watch("/marker", "visualization_msgs/Marker", keep_every=True) == ""
        assert "already shown as" in source.watch("/scan", "nav_msgs/Path", keep_every=False)
        assert "unknown message type" in source.watch("/x", "no_msgs/Nothing", keep_every=False)
        connected = {"/scan": threading.Event(), "/marker": threading.Event()}
        scans = talker.advertise("/scan", LaserScan._type, LaserScan._md5sum, LaserScan._full_text,
                                 on_connect=lambda link: connected["/scan"].set())
        marks = talker.advertise("/marker", Marker._type, Marker._md5sum, Marker._full_text,
                                 on_connect=lambda link: connected["/marker"].set())
        assert all(event.wait(10) for event in connected.values())
        for i in range(50):
            scans.publish_frame(serialize_frame(LaserScan(range_max=float(i))))
        for i in range(5):
            marks.publish_frame(serialize_frame(Marker(id=i)))
        taken: dict[str, list[Any]] = {"/scan": [], "/marker": []}

        def complete() -> bool:
            return len(taken["/marker"]) == 5 and bool(taken["/scan"]) and taken["/scan"][-1].range_max == 49.0

        while not complete():  # the window's turns: woken, it takes what waits
            assert woken.wait(10), taken
            woken.clear()
            for topic, messages in source.take().items():
                if topic == "/scan":
                    assert len(messages) <= 1  # latest wins
                taken[topic] += messages
        assert [m.id for m in taken["/marker"]] == [0, 1, 2, 3, 4]

        transform = TransformStamped()
        transform.header.frame_id, transform.child_frame_id = "map", "laser"
        transform.transform.translation.x = 2.0
        transform.transform.rotation.w = 1.0
        source.buffer.set_transform(transform, "test")
        frames = source.frames("map")
        assert frames.transform("laser")[:3, 3] == pytest.approx(np.array([2.0, 0.0, 0.0]))  # type: ignore[index]
        assert "no transform from base_link to map" in str(frames.transform("base_link"))
        assert frames.names() == ["laser", "map"] and frames.parent("laser") == "map"



def test_marker_arrays_wait_as_bytes_while_the_window_is_busy_and_only_those_that_matter_are_decoded(
        tmp_path: Path) -> None:
    from kame.rviz import markers

    def array(index: int, action: int = markers.ADD, ids: range = range(10), skip: int = -1) -> MarkerArray:
        return MarkerArray(markers=[Marker(ns="flood", id=i, action=action, pose=Pose(position=Point(x=index)))
                                    for i in ids if i != skip])

    woken = threading.Event()
    with rviz_with(tmp_path, "/talker", woken.set) as (source, talker):
        assert source.watch("/markers", "visualization_msgs/MarkerArray", keep_every=True) == ""
        connected = threading.Event()
        arrays = talker.advertise("/markers", MarkerArray._type, MarkerArray._md5sum, MarkerArray._full_text,
                                  on_connect=lambda link: connected.set())
        assert connected.wait(10)
        arrays.publish_frame(serialize_frame(array(0)))
        assert woken.wait(10)  # decoded; the window has not taken it yet
        woken.clear()
        backlog = [array(i) for i in range(1, 11)] + [array(11, markers.DELETE, range(3, 4)), array(12, skip=3)]
        for message in backlog:
            arrays.publish_frame(serialize_frame(message))
        deadline = time.monotonic() + 30
        while len(source._waiting.get("/markers", [])) < len(backlog):  # nothing decoded meanwhile
            assert time.monotonic() < deadline and not woken.is_set(), source._waiting
            time.sleep(0.01)
        display = markers.MarkerArray()
        first = source.take()["/markers"]
        assert [m.markers[0].pose.position.x for m in first] == [0.0]
        display.receive(first, 0.0)
        assert woken.wait(10)  # taking woke the decoder: of the backlog, the DELETE and the newest
        last = source.take()["/markers"]
        assert [m.markers[0].pose.position.x for m in last] == [11.0, 12.0]
        display.receive(last, 1.0)
        assert sorted(display.markers) == [("flood", i) for i in range(10) if i != 3]
        assert {m.pose.position.x for m, _ in display.markers.values()} == {12.0}

def test_scans_and_maps_are_decoded_into_arrays_and_drawn_as_from_tuples() -> None:
    from kame.rviz import displays
    from kame.rviz.source import decode
    from nav_msgs.msg import OccupancyGrid
    from tests.rviz.test_model import build

    def payload(message: Any) -> bytes:
        return b"".join(bytes(part) for part in serialize_frame(message))[4:]

    grid = OccupancyGrid(data=[0, 100, -1, 50])
    grid.header.frame_id = "map"
    grid.info.width, grid.info.height, grid.info.resolution = 2, 2, 0.5
    grid.info.origin.orientation.w = 1.0
    scan = LaserScan(angle_min=0.0, angle_increment=0.5, range_min=0.1, range_max=10.0, ranges=[1.0, 2.0, 99.0],
                     intensities=[1.0, 2.0, 3.0])
    scan.header.frame_id = "laser"
    for message, display_class, array in ((grid, displays.OccupancyGrid, "data"), (scan, displays.LaserScan, "ranges")):
        fast = decode(type(message), payload(message))
        assert isinstance(getattr(fast, array), np.ndarray)
        plain = type(message)._from_buffer(memoryview(payload(message)))
        ours, theirs = build(display_class(), fast), build(display_class(), plain)
        for a, b in zip(ours.batches + ours.textures, theirs.batches + theirs.textures, strict=True):
            for field in ("vertices", "colors", "rgba", "corners"):
                if hasattr(a, field):
                    assert np.array_equal(getattr(a, field), getattr(b, field)), (display_class, field)
        assert len(ours.batches) + len(ours.textures) == 1
    marker = decode(Marker, payload(Marker(ns="n")))  # no numbers to speak of: decoded as usual
    assert marker.ns == "n"


def test_sim_time_going_back_clears_rvizs_tf_buffer(tmp_path: Path) -> None:
    """Under /use_sim_time, /clock going back (a bag played in a loop with --clock) clears the
    source's tf buffer, as rviz's does, so the fixed frame's old transforms do not linger."""
    from rosgraph_msgs.msg import Clock
    from tf2_msgs.msg import TFMessage

    with rviz_with(tmp_path, "/player", lambda: None, sim_time=True) as (source, player):
        connected = {"/clock": threading.Event(), "/tf": threading.Event()}
        clock = player.advertise("/clock", Clock._type, Clock._md5sum, Clock._full_text,
                                 on_connect=lambda link: connected["/clock"].set())
        tf = player.advertise("/tf", TFMessage._type, TFMessage._md5sum, TFMessage._full_text,
                              on_connect=lambda link: connected["/tf"].set())
        assert all(event.wait(10) for event in connected.values())

        def play(seconds: float) -> None:
            """/clock at `seconds`, and once rviz's clock reads it a transform stamped then (on
            their two connections a transform could overtake its clock: received at the clock's
            previous time, as a bag's first message before the first /clock is in ROS too)."""
            now = Time.from_sec(seconds)
            clock.publish_frame(serialize_frame(Clock(clock=now)))
            deadline = time.monotonic() + 20
            while source.clock.now_ns() != now.to_nsec():
                assert time.monotonic() < deadline, f"rviz's clock never read {seconds} s"
                time.sleep(0.01)
            moved = TransformStamped()
            moved.header.stamp, moved.header.frame_id, moved.child_frame_id = now, "map", "base"
            moved.transform.rotation.w = 1.0
            tf.publish_frame(serialize_frame(TFMessage(transforms=[moved])))

        def known(seconds: float, wait: float = 0.0) -> bool:
            return bool(source.buffer.can_transform("map", "base", Time.from_sec(seconds), Duration.from_sec(wait)))

        play(100.0)
        assert known(100.0, wait=20.0), "the first transform never arrived"
        play(50.0)
        assert known(50.0, wait=20.0), "the transform after the jump never arrived"
        assert not known(100.0)  # cleared when time went back
