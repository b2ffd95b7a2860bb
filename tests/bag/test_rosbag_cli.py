"""rosbag on the command line, end to end against kame's roscore: record (limit, Ctrl-C, a
killed recorder repaired by reindex), play into a subscriber, filter, compress, decompress.
Every process is started through tests.support.Proc and stopped by its PID."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

import rosbag
from tests.support import Proc, free_port, ros_env, wait_for_master

BIN = Path(sys.executable).parent


@pytest.fixture(scope="module")
def core(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, str]]:
    home = tmp_path_factory.mktemp("bagcli")
    port = free_port()
    env = ros_env(home, f"http://127.0.0.1:{port}/")
    proc = Proc([str(BIN / "roscore"), "-p", str(port)], env)
    try:
        wait_for_master(env["ROS_MASTER_URI"], proc=proc)
        yield env
    finally:
        proc.stop()


def _run(env: dict[str, str], *args: str, cwd: Path, timeout: float = 30) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(BIN / "rosbag"), *args], env=env, cwd=cwd, capture_output=True, text=True,
                          timeout=timeout)


def _talker(env: dict[str, str], topic: str = "/chatter", rate: str = "100") -> Proc:
    return Proc([str(BIN / "rostopic"), "pub", "-r", rate, topic, "std_msgs/String", "data: hi"], env)


def test_record_with_limit_then_play_into_a_subscriber(core: dict[str, str], tmp_path: Path) -> None:
    talker = _talker(core)
    try:
        res = _run(core, "record", "-O", "rec", "/chatter", "-l", "20", cwd=tmp_path)
    finally:
        talker.stop()
    assert res.returncode == 0, res.stderr
    assert "Subscribing to /chatter" in res.stdout and "Recording to 'rec.bag'." in res.stdout
    with rosbag.Bag(tmp_path / "rec.bag") as bag:
        msgs = list(bag.read_messages(return_connection_header=True))
    assert len(msgs) == 20 and all(m.message.data == "hi" for m in msgs)
    assert msgs[0].connection_header["callerid"].startswith("/rostopic_")
    echo = Proc([str(BIN / "rostopic"), "echo", "/chatter", "-n", "5"], core)
    try:
        # -d alone is a guess at how long the echo takes to find the topic and connect: the 20
        # messages go out in 50 ms, so a slow echo missed them. Wait for the subscriber too.
        play = _run(core, "play", "-q", "-r", "4", "-d", "0.5", "--wait-for-subscribers", "rec.bag", cwd=tmp_path)
        assert play.returncode == 0, play.stderr
        assert "Hit space to toggle paused, or 's' to step." in play.stdout and play.stdout.endswith("Done.\n")
        echo.popen.wait(10)
    finally:
        out, _ = echo.stop()
    assert out.count('data: "hi"') == 5


def wait_for_bytes(path: Path, size: int = 20_000, timeout: float = 30.0) -> None:
    """Until the recorder has written `size` bytes of chunks (a String 'hi' takes under 70 bytes
    with its index, so 20 kB is well over the 100 messages the test wants), not for a fixed time:
    under load the talker and the recorder's connection can take most of a second or two to get going."""
    deadline = time.monotonic() + timeout
    while not (path.exists() and path.stat().st_size > size):
        assert time.monotonic() < deadline, f"{path} did not reach {size} bytes in {timeout}s"
        time.sleep(0.05)


def test_ctrl_c_closes_and_kill_is_repaired_by_reindex(core: dict[str, str], tmp_path: Path) -> None:
    talker = _talker(core, "/fast", "500")
    try:
        rec = Proc([str(BIN / "rosbag"), "record", "-O", "clean", "-a", "--chunksize", "4"], core, cwd=tmp_path)
        rec.wait_line("Recording to")
        wait_for_bytes(tmp_path / "clean.bag.active")
        rec.stop()
        assert (tmp_path / "clean.bag").exists() and not (tmp_path / "clean.bag.active").exists()
        with rosbag.Bag(tmp_path / "clean.bag") as bag:
            assert bag.get_message_count("/fast") > 100
        killed = Proc([str(BIN / "rosbag"), "record", "-O", "killed", "/fast", "--chunksize", "4"], core, cwd=tmp_path)
        killed.wait_line("Recording to")
        wait_for_bytes(tmp_path / "killed.bag.active")
        os.kill(killed.pid, signal.SIGKILL)
        killed.stop()
    finally:
        talker.stop()
    active = tmp_path / "killed.bag.active"
    assert active.exists()
    with pytest.raises(rosbag.ROSBagUnindexedException):
        rosbag.Bag(active)
    res = _run(core, "reindex", str(active), cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    with rosbag.Bag(active) as bag:
        assert bag.get_message_count() > 100


def test_filter_compress_decompress(core: dict[str, str], tmp_path: Path) -> None:
    from rospy import Time
    from std_msgs.msg import String

    with rosbag.Bag(tmp_path / "in.bag", "w") as bag:
        for i in range(200):
            bag.write("/a" if i % 2 else "/b", String(data=str(i)), Time(10 + i, 0))
    res = _run(core, "filter", "in.bag", "out.bag", "topic == '/a' and int(m.data) > 100", cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    with rosbag.Bag(tmp_path / "out.bag") as bag:
        assert [m.message.data for m in bag.read_messages()] == [str(i) for i in range(101, 200, 2)]
    for args, kind in ((["compress", "--lz4"], "lz4"), (["compress"], "bz2"), (["decompress"], "none")):
        res = _run(core, *args, "-f", "in.bag", cwd=tmp_path)
        assert res.returncode == 0, res.stderr
        with rosbag.Bag(tmp_path / "in.bag") as bag:
            assert bag.get_compression_info().compression == kind
            assert [m.message.data for m in bag.read_messages()] == [str(i) for i in range(200)]
    assert (tmp_path / "in.orig.bag").exists()
    res = _run(core, "compress", "in.bag", cwd=tmp_path)
    assert "Skipping in.bag. Backup path in.orig.bag already exists." in res.stderr


def test_play_of_a_bag_damaged_past_its_index_plays_what_it_can_then_says_why(core: dict[str, str],
                                                                               tmp_path: Path) -> None:
    from kame.bag.reader import BagReader
    from rospy import Time
    from std_msgs.msg import String

    path = tmp_path / "d.bag"
    with rosbag.Bag(path, "w", chunk_threshold=300) as bag:
        for i in range(30):
            bag.write("/d", String(data="x" * i), Time(100, i * 10_000_000))
    data = bytearray(path.read_bytes())
    with BagReader(path) as reader:
        pos = reader.chunk_infos[-1].pos
    data[pos:pos + 4] = (0xFFFFFFF0).to_bytes(4, "little")  # the last chunk's header length
    path.write_bytes(data)
    play = _run(core, "play", "-q", "-d", "0", "d.bag", cwd=tmp_path)
    assert play.returncode == 1
    assert "Traceback" not in play.stderr
    assert "[FATAL]" in play.stderr and "claims a 4294967280-byte header" in play.stderr


def test_record_into_a_missing_folder_or_onto_a_full_disk_says_so_and_ends(core: dict[str, str],
                                                                           tmp_path: Path) -> None:
    import resource

    talker = Proc([str(BIN / "rostopic"), "pub", "-r", "50", "/big", "std_msgs/String", "data: " + "x" * 20000], core)
    try:
        res = _run(core, "record", "-O", str(tmp_path / "missing" / "r.bag"), "/big", cwd=tmp_path)
        assert res.returncode == 1
        assert f"Error writing: Error opening file: {tmp_path}/missing/r.bag.active" in res.stderr
        assert not (tmp_path / "missing").exists()  # rosbag makes no folder for it

        def small_files() -> None:  # a full disk, as the writer sees it: EFBIG past 100 KB
            resource.setrlimit(resource.RLIMIT_FSIZE, (100_000, 100_000))

        full = subprocess.run([str(BIN / "rosbag"), "record", "-O", "f.bag", "/big"], env=core, cwd=tmp_path,
                              capture_output=True, text=True, timeout=30, preexec_fn=small_files)
    finally:
        talker.stop()
    assert full.returncode == 1
    assert "Error writing: cannot write f.bag.active: File too large" in full.stderr
    assert "Traceback" not in full.stderr


def test_record_with_a_duration_ends_on_time_with_no_messages(core: dict[str, str], tmp_path: Path) -> None:
    # The writer waits on its queue until the duration is up, not for a message that never comes
    # (rosbag's recorder checks the duration while idle too).
    res = _run(core, "record", "-O", "idle", "--duration=1", "/nobody_publishes", cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    with rosbag.Bag(tmp_path / "idle.bag") as bag:
        assert bag.get_message_count() == 0
    assert not (tmp_path / "idle.bag.active").exists()
