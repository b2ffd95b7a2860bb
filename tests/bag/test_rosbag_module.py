"""rosbag.Bag as ROS 1's on open file objects, its argument checks, its start and end times
while writing and when empty, rosbag.bag's record helpers and a Bag's private attributes, and
an uninitialised AnyMsg: the same cases through Debian's real rosbag (tests/bag/rosbag_module_driver.py)."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import pytest

from ..libs import debian

DRIVER = Path(__file__).with_name("rosbag_module_driver.py")


def answers(python: str | Path, folder: Path) -> Any:
    folder.mkdir()
    return debian.run(DRIVER, {"folder": str(folder)}, python=python)


@pytest.fixture(scope="module")
def kame(tmp_path_factory: pytest.TempPathFactory) -> Any:
    return answers(sys.executable, tmp_path_factory.mktemp("rosbag") / "kame")


@pytest.fixture(scope="module")
def ros(tmp_path_factory: pytest.TempPathFactory) -> Any:
    if not debian.has("rosbag", "std_msgs.msg"):
        pytest.skip("Debian's rosbag is not installed")
    return answers(debian.SYSTEM_PYTHON, tmp_path_factory.mktemp("rosbag") / "ros")


def test_a_bag_on_an_open_file_object(kame: Any, ros: Any) -> None:
    assert kame["file_objects"]["read"]["messages"] == [["/a", "one", 1_000_000_002], ["/b", "two", 3_000_000_000]]
    assert kame["file_objects"]["read"]["filename"] is None
    assert kame["file_objects"] == ros["file_objects"]


def test_arguments_are_checked_before_the_file_is_opened(kame: Any, ros: Any) -> None:
    assert kame["argument_checks"]["chunk_threshold"] == [
        "raised", "ValueError", "chunk_threshold must be greater than or equal to zero"]
    assert kame["argument_checks"] == ros["argument_checks"]


def test_start_and_end_times_of_empty_and_writing_bags(kame: Any, ros: Any) -> None:
    assert kame["times"]["writing_empty"][0] == ["raised", "ROSBagException", "Bag contains no message"]
    assert kame["times"] == ros["times"]


def test_record_helpers_and_private_attributes(kame: Any, ros: Any) -> None:
    assert kame["record_helpers"]["version"] == 200
    assert kame["record_helpers"] == ros["record_helpers"]


def test_an_uninitialised_anymsg_raises_rosexception(kame: Any, ros: Any) -> None:
    assert kame["any_msg"] == ["raised", "ROSException", "AnyMsg is not initialized"] == ros["any_msg"]


def test_rosbag_main_parts(kame: Any, ros: Any) -> None:
    """bag_op with change_compression_op and reindex_op, ProgressMeter, RosbagCmds, the option callbacks."""
    assert kame["main_parts"]["compressed"][1][0] == "bz2" and kame["main_parts"]["compressed"][2]
    assert kame["main_parts"]["options"][:4] == [["/a", "/b"], ["/c"], True, 12]
    assert kame["main_parts"] == ros["main_parts"]
