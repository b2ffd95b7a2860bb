"""The new plugins' models without a window or a network: message trees and field expressions
(rqt_topic, rqt_publisher, rqt_service_caller), rates (rqt_topic) and pixels (rqt_image_view)."""

from __future__ import annotations

import struct

import numpy as np
import pytest

from geometry_msgs.msg import PoseStamped, Twist
from kame.rostime import Time
from kame.rqt.image_model import ImageError, to_display
from kame.rqt.message_tree import ExpressionError, build_message, editable_fields, evaluate, value_tree
from kame.rqt.topic_model import TopicStats, bandwidth_text, rate_text
from sensor_msgs.msg import Image, JointState
from std_msgs.msg import Float64MultiArray


def test_a_message_as_an_expandable_tree() -> None:
    pose = PoseStamped()
    pose.header.stamp = Time(12, 5)
    pose.header.frame_id = "map"
    pose.pose.position.x = 1.5
    tree = value_tree(pose)
    assert [(r.name, r.type) for r in tree.children] == [("header", "std_msgs/Header"), ("pose", "geometry_msgs/Pose")]
    header = tree.children[0]
    assert [(r.name, r.value) for r in header.children] == [("seq", "0"), ("stamp", "12.000000005"),
                                                            ("frame_id", "'map'")]
    assert tree.children[1].children[0].children[0] == value_tree(1.5, "x", "float64")
    joints = value_tree(JointState(name=["a", "b"], position=[0.5] * 100))
    names, positions = joints.children[1], joints.children[2]
    assert (names.value, [r.value for r in names.children]) == ("2 items", ["'a'", "'b'"])
    assert positions.value == "100 items" and len(positions.children) == 65
    assert positions.children[-1].value == "36 more"
    image = value_tree(Image(data=bytes(range(40))))
    assert image.children[-1].value.startswith("40 bytes [0, 1, 2,") and image.children[-1].children == ()


def test_editable_fields_and_expressions_as_rqt_publisher_has_them() -> None:
    assert editable_fields(Twist) == [("linear/x", "float64"), ("linear/y", "float64"), ("linear/z", "float64"),
                                      ("angular/x", "float64"), ("angular/y", "float64"), ("angular/z", "float64")]
    assert ("header/stamp", "time") in editable_fields(PoseStamped)
    assert ("data", "float64[]") in editable_fields(Float64MultiArray)
    assert evaluate("i * 2 + math.pi", 3) == pytest.approx(6 + 3.141592653589793)
    assert 0 <= evaluate("random.random()", 0) < 1
    twist = build_message(Twist, {"linear/x": "2.0", "angular/z": "math.sin(i)", "linear/y": ""}, i=1)
    assert (twist.linear.x, twist.angular.z, twist.linear.y) == (2.0, pytest.approx(0.8414709848), 0.0)
    array = build_message(Float64MultiArray, {"data": "[i, i + 1]"}, i=4)
    assert list(array.data) == [4, 5]
    stamped = build_message(PoseStamped, {"header/stamp": "1_500_000_000", "header/frame_id": "'map'"})
    assert (stamped.header.stamp, stamped.header.frame_id) == (Time(1, 500_000_000), "map")
    with pytest.raises(ExpressionError, match="linear/x: 'nope': NameError"):
        build_message(Twist, {"linear/x": "nope"})
    with pytest.raises(ExpressionError, match="Division"):
        build_message(Twist, {"linear/x": "1/0"})


def test_rate_and_bandwidth_over_the_window() -> None:
    stats = TopicStats(window=10)
    assert (stats.rate(), stats.bandwidth()) == (None, None)
    for n in range(25):  # 20 Hz, 100 bytes each
        stats.add(n * 0.05, 100)
    assert stats.count == 25
    assert stats.rate() == pytest.approx(20.0) and stats.bandwidth() == pytest.approx(2000.0)
    assert (rate_text(stats.rate()), bandwidth_text(stats.bandwidth())) == ("20.00", "2.00KB/s")
    assert (bandwidth_text(512.0), bandwidth_text(3.5e6), rate_text(None)) == ("512.00B/s", "3.50MB/s", "")


def test_each_encoding_becomes_display_pixels() -> None:
    rgb = bytes([255, 0, 0, 0, 255, 0, 9, 9])  # 2x1 red, green, and 2 bytes of row padding
    assert to_display("rgb8", 2, 1, 8, rgb)[0].tolist() == [[255, 0, 0], [0, 255, 0]]
    assert to_display("bgr8", 2, 1, 8, rgb)[0].tolist() == [[0, 0, 255], [0, 255, 0]]
    assert to_display("bgra8", 1, 1, 4, bytes([1, 2, 3, 4]))[0].tolist() == [[3, 2, 1, 4]]
    assert to_display("rgba8", 1, 1, 4, bytes([1, 2, 3, 4]))[0].tolist() == [[1, 2, 3, 4]]
    assert to_display("mono8", 3, 1, 3, bytes([0, 128, 255])).reshape(-1).tolist() == [0, 128, 255]
    mono16 = struct.pack("<2H", 0x1234, 0xFF00)
    assert to_display("mono16", 2, 1, 4, mono16).reshape(-1).tolist() == [0x12, 0xFF]
    assert to_display("mono16", 2, 1, 4, struct.pack(">2H", 0x1234, 0xFF00), True).reshape(-1).tolist() == [0x12, 0xFF]
    depth_mm = struct.pack("<4H", 0, 1000, 2000, 3000)  # 0: unknown depth, black
    assert to_display("16UC1", 4, 1, 8, depth_mm).reshape(-1).tolist() == [0, 0, 128, 255]
    depth_m = struct.pack("<4f", float("nan"), 0.5, 1.0, float("inf"))
    assert to_display("32FC1", 4, 1, 16, depth_m).reshape(-1).tolist() == [0, 0, 255, 0]
    assert to_display("32FC1", 1, 1, 4, struct.pack("<f", 2.0)).reshape(-1).tolist() == [255]
    pixels = to_display("rgb8", 2, 1, 8, rgb)
    assert pixels.flags["C_CONTIGUOUS"] and pixels.dtype == np.uint8


def test_images_that_do_not_add_up_are_refused() -> None:
    for args, why in ((("yuv422", 1, 1, 2, b"ab"), "not shown"), (("rgb8", 2, 1, 5, bytes(6)), "step 5"),
                      (("rgb8", 2, 2, 6, bytes(6)), "12 needed"), (("mono8", 0, 0, 0, b""), "empty")):
        with pytest.raises(ImageError, match=why):
            to_display(*args)
