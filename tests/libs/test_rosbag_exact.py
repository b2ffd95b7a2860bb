"""rosbag.Bag's edges as rosbag has them: wall-time stamps without a node, file objects, closed
bags, rosbag's exception types and texts."""

from __future__ import annotations

import io
import time
from pathlib import Path

import pytest

import rosbag
from genpy import Time
from std_msgs.msg import Int32


def test_write_without_a_time_stamps_wall_time_without_a_node(tmp_path: Path) -> None:
    path = tmp_path / "wall.bag"
    before = time.time()
    with rosbag.Bag(str(path), "w") as bag:
        bag.write("/a", Int32(1))
    after = time.time()
    with rosbag.Bag(str(path)) as bag:
        (_, msg, stamp), = list(bag.read_messages())
    assert msg.data == 1 and before - 1e-6 <= stamp.to_sec() <= after + 1e-6


def test_read_messages_is_in_time_order_across_chunks(tmp_path: Path) -> None:
    path = tmp_path / "chunks.bag"
    stamps = [5, 3, 9, 1, 7, 2, 8, 4, 6]
    with rosbag.Bag(str(path), "w", chunk_threshold=100) as bag:
        for index, secs in enumerate(stamps):
            bag.write("/b" if index % 2 else "/a", Int32(index), Time(secs))
    with rosbag.Bag(str(path)) as bag:
        assert len(bag._read_side().chunk_infos) > 2  # the messages do span chunks
        assert [t.secs for _, _, t in bag.read_messages()] == sorted(stamps)
        assert [t.secs for _, _, t in bag.read_messages(topics=["/b"])] == sorted(stamps[1::2])


def test_open_on_a_file_object(tmp_path: Path) -> None:
    path = tmp_path / "f.bag"
    with rosbag.Bag(str(path), "w") as bag:
        bag.write("/a", Int32(7), Time(1))
    with open(path, "rb") as f, rosbag.Bag(f) as bag:
        assert [m.data for _, m, _ in bag.read_messages()] == [7]
        assert bag.size == path.stat().st_size
        assert not f.closed
    with pytest.raises(ValueError, match="not a stream"):
        rosbag.Bag(io.BytesIO(), "w")


def test_closed_bags_and_bad_arguments(tmp_path: Path) -> None:
    path = tmp_path / "c.bag"
    with rosbag.Bag(str(path), "w") as bag:
        bag.write("/a", Int32(7), Time(1))
    with pytest.raises(ValueError, match="I/O operation on closed bag"):
        _ = bag.size
    reader = rosbag.Bag(str(path))
    reader.close()
    assert reader.get_message_count() == 1 and reader.get_start_time() == 1.0  # the index stays
    with pytest.raises(ValueError, match="I/O operation on closed bag"):
        list(reader.read_messages())
    with pytest.raises(ValueError, match=r"filename \(or stream\) is invalid"):
        rosbag.Bag("")
    with pytest.raises(ValueError, match='mode "x" is invalid'):
        rosbag.Bag(str(path), "x")
    with rosbag.Bag(str(path)) as bag, pytest.raises(io.UnsupportedOperation):
        bag.write("/a", Int32(1))


def test_rosbag_exceptions_carry_value(tmp_path: Path) -> None:
    error = rosbag.ROSBagException("broken")
    assert error.value == "broken" and str(error) == "broken"
    junk = tmp_path / "junk.bag"
    junk.write_bytes(b"not a bag" * 20)
    with pytest.raises(rosbag.ROSBagException) as caught:
        rosbag.Bag(str(junk))
    assert "is not a bag file" in str(caught.value.value)
    empty = tmp_path / "empty.bag"
    rosbag.Bag(str(empty), "w").close()
    with rosbag.Bag(str(empty)) as bag, pytest.raises(rosbag.ROSBagException, match="Bag contains no message"):
        bag.get_start_time()
